// Two vehicles mapping two far corners of the test hall, five temporary maps each, for the
// restart test. Their maps lie at least 6 m apart, so no merge of one vehicle touches a cell
// (or a neighbour of a cell) that the other's merges touch: the current map does not depend
// on how the two vehicles' maps interleave, only on each vehicle's own order.
#pragma once

#include <string>
#include <vector>

#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator::node::testing {

inline core::OccupancyGrid FleetWorld() {
  return aggregator::testing::HallMap(0.0, {{{5.0, 5.0}, {1.2, 0.8}}, {{16.5, 4.5}, {0.8, 1.2}}});
}

// Vehicle "a" near the corner (0, 0) heading +x, vehicle "b" near (20, 0) heading -x; maps
// 8 m square (3 x 3 tiles), 20 s apart, sequences 1..count.
inline std::vector<core::TempMap> FleetMaps(const std::string& vehicle, int count = 5) {
  const core::OccupancyGrid world = FleetWorld();
  std::vector<core::TempMap> maps;
  for (int i = 0; i < count; ++i) {
    aggregator::testing::TempMapSpec spec;
    spec.start = vehicle == "a" ? core::Pose2(2.313 + 0.1 * i, 2.817, 0.0)
                                : core::Pose2(17.687 - 0.1 * i, 2.217, M_PI);
    spec.grid_m = 8.0;
    spec.anchor_error = {0.05 * (i % 3) - 0.05, 0.04 * (i % 2) - 0.02, (i % 3 - 1) * M_PI / 180};
    spec.vehicle = vehicle;
    spec.sequence = i + 1;
    spec.start_s = 2000.0 + 20.0 * i;
    spec.end_s = spec.start_s + 10.0;
    spec.seed = (vehicle == "a" ? 100 : 200) + i;
    maps.push_back(aggregator::testing::BuildTempMap(world, spec));
  }
  return maps;
}

}  // namespace fleetmap::aggregator::node::testing
