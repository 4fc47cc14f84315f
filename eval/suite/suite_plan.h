// Which worlds the suite runs: generated buildings of every style at fixed seeds, turns,
// resolutions and sizes, every public map found in the worlds folder, and the LivingLab hall
// the method was first measured on (docs/world_suite.md).
#pragma once

#include <string>
#include <vector>

#include "sim/worldgen/world_generator.h"

namespace fleetmap::eval::suite {

enum class WorldSource { kGenerated, kPublic, kLivingLab };

struct SuiteWorld {
  std::string name;   // unique, used in figure names and folder names
  std::string group;  // the style for generated worlds, "public", "livinglab"
  WorldSource source = WorldSource::kGenerated;
  sim::worldgen::WorldOptions generated;  // kGenerated
  std::string map_yaml;                   // kPublic: the map_server file
  std::string scenario_yaml;              // kLivingLab: the shipped scenario
};

struct PlanOptions {
  bool quick = false;  // about 8 worlds of a few minutes, for the test suite
  // The folder of public maps (<name>/<map>.yaml each); empty or absent: none, said so.
  std::string worlds_dir;
  std::string livinglab_scenario;  // empty: the LivingLab is left out
};

struct SuitePlan {
  std::vector<SuiteWorld> worlds;
  std::vector<std::string> notes;  // what was left out and why (no worlds folder, ...)
};

SuitePlan PlanSuite(const PlanOptions& options);

}  // namespace fleetmap::eval::suite
