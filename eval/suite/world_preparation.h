// Makes a suite world ready to run: the map on disk (generated, or a public map checked that
// it can carry a scenario) and a scenario on it. A world that cannot be used is refused with
// the reason, so that the suite reports it by name and leaves it out of the aggregate.
#pragma once

#include <string>

#include "core/result.h"
#include "eval/suite/suite_plan.h"
#include "sim/worldgen/scenario_writer.h"

namespace fleetmap::eval::suite {

struct PreparedWorld {
  std::string scenario_yaml;
  double resolution_m = 0.0;
  double width_m = 0.0, height_m = 0.0;  // the map's grid
  std::string fitted;                    // what the scenario writer left out on a small floor
};

// Checks a map before any scenario is planned on it: FailedPrecondition names what it lacks
// (an empty grid, nothing observed, no free space, no wall).
core::Status CheckMapUsable(const core::OccupancyGrid& map);

// Writes into `folder`: map.{yaml,pgm,png} for generated worlds and scenario.yaml.
core::Result<PreparedWorld> PrepareWorld(const SuiteWorld& world, const std::string& folder,
                                         const sim::worldgen::ScenarioOptions& scenario);

}  // namespace fleetmap::eval::suite
