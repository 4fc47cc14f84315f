// Small worlds built in code for the simulator tests.
#pragma once

#include <string>

#include "core/map/occupancy_grid.h"

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

// A scenario in Room(): a box there from the start, one that appears at 5 s and goes at 40 s;
// one vehicle drives back and forth past both for 70 s.
constexpr const char* kRoomWithBoxesScenario = R"(
name: room
map: room.yaml
duration_s: 70
seed: 4
objects:
  - {id: box_a, rect: {center: [3, 1.5], size: [0.8, 0.6]}}
  - {id: box_b, rect: {center: [7, 4.5], size: [1.0, 0.8]}, appear_s: 5, disappear_s: 40}
vehicles:
  - {id: v1, route: [[1.013, 3.027], [9.013, 3.027]], loop: true, speed_mps: 1.0}
)";

inline std::string LivingLabDir() {
  return std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/";
}

}  // namespace fleetmap::sim::testing
