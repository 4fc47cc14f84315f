// A scenario on any map (generated or a user's own map_server file): vehicles on loops planned
// through free space with clearance, pallets appearing beside their routes while they drive
// and others taken away, people crossing the routes and turning, a forklift that drives along
// a route and stops. What changes is placed where a vehicle passes again after the change,
// so that the fleet can see it (docs/worldgen.md).
#pragma once

#include <cstdint>
#include <string>

#include "core/map/occupancy_grid.h"
#include "core/result.h"
#include "sim/scenario.h"

namespace fleetmap::sim::worldgen {

struct ScenarioOptions {
  uint32_t seed = 1;
  double duration_s = 300.0;
  int vehicles = 3;  // 1 to 5; scanners S300, microScan3, TiM571, LMS111 in turn
  double vehicle_speed_mps = 0.5;
  // Longest loop a vehicle drives; 0: speed * duration / 2.5, so that it passes every place
  // on its loop more than twice in the run.
  double max_loop_m = 0.0;
  double vehicle_clearance_m = 0.6;  // route to the nearest wall, object or unknown cell
  int objects_added = 4;             // pallets that appear while the fleet drives
  int objects_removed = 1;           // pallets there at the start, taken away during the run
  double object_gap_m = 0.3;  // beyond the vehicle's clearance, between an object and a route
  int people = 2;             // crossing routes back and forth; every other one stands a while
  int forklifts = 1;          // along a route, stopping at each end
  // The vehicles' systematic odometry error (sim::OdometryNoise::scale_sigma,
  // heading_drift_sigma_rad_m): at the level of the SLAM benchmark logs' own odometry (off by
  // a median of 3.3 % and 3.6 deg per metre over 0.3-2 m on intel, 7.3 % and 3.1 deg/m on
  // fr079; docs/scenario.md), so that the suite does not reward trusting the wheels.
  double odometry_scale_sigma = 0.05;
  double odometry_heading_drift_sigma_rad_m = 0.06;
  // On a floor too small for all of the above (a shop, a corridor), rather than no scenario
  // at all: where no object fits, fewer vehicles (down to one), then fewer objects appearing
  // (down to one), then loops of a half and a quarter of the length; where no forklift nor
  // cart fits, none; where a person does not fit, fewer people (down to one).
  bool fit_to_floor = true;
  core::Status Validate() const;
};

struct WrittenScenario {
  sim::Scenario scenario;
  std::string fitted;  // what fit_to_floor changed ("2 vehicle(s) instead of 3"); empty: nothing
};

// `map_yaml` is what the scenario names as its map. FailedPrecondition names what the map
// lacks (no free space with the clearance, no room for a route or an object).
core::Result<WrittenScenario> WriteScenarioFor(const core::OccupancyGrid& map,
                                               const std::string& map_yaml,
                                               const ScenarioOptions& options);

}  // namespace fleetmap::sim::worldgen
