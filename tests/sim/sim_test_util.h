// Small worlds built in code for the simulator tests.
#pragma once

#include <string>

#include "core/occupancy_grid.h"

namespace fleetmap::sim::testing {

// A free 10 m x 6 m room at 5 cm with one-cell walls around it.
inline core::OccupancyGrid Room() {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 200, 120));
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 200; ++x)
      grid.SetState({x, y}, (x == 0 || y == 0 || x == 199 || y == 119) ? core::CellState::kOccupied
                                                                       : core::CellState::kFree);
  return grid;
}

inline std::string LivingLabDir() {
  return std::string(FLEETMAP_SOURCE_DIR) + "/tools/sim/worlds/livinglab/";
}

}  // namespace fleetmap::sim::testing
