// A small simulated world for the CAN tests: a 10 m x 6 m room, one vehicle driving a loop
// with four turns, odometry at 50 Hz (the SYNC rate of the encoded drive nodes).
#pragma once

#include <string>

#include "sim/world.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::sim::can::testing {

constexpr const char* kLoopScenario = R"(
map: room.yaml
duration_s: 60
seed: 7
vehicles:
  - id: agv
    scanner: TiM571
    route: [[1, 1], [8, 1], [8, 5], [1, 5]]
    loop: true
    speed_mps: 1.0
    angular_speed_radps: 1.0
)";

inline sim::World LoopWorld() {
  return sim::World::Create(sim::ParseScenario(kLoopScenario, "loop.yaml").value(),
                            sim::testing::Room())
      .value();
}

}  // namespace fleetmap::sim::can::testing
