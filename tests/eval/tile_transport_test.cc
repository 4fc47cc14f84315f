#include "eval/tile_transport.h"

#include <gtest/gtest.h>

#include "core/codec/cell_packing.h"

namespace fleetmap::eval {
namespace {

// 150 x 90 cells (3 x 2 tiles of 64), log-odds in a ramp over the clamped range, a trajectory.
core::TempMap Sample() {
  core::TempMap map;
  map.vehicle_id = "cts2";
  map.sequence = 7;
  map.anchor_in_map = {12.3, 4.5, 0.4};
  map.start_s = 10.0;
  map.end_s = 13.0;
  map.grid = core::OccupancyGrid(core::GridGeometry(0.05, 150, 90, {-3.0, -2.0, 0.0}));
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 150; ++x) map.grid.SetLogOdds({x, y}, -4.6f + 0.00071f * (y * 150 + x));
  map.trajectory_in_temp = {{10.0, {}}, {10.04, {0.02, 0.0, 0.0}}};
  return map;
}

TEST(TileTransportTest, TheAggregatorGetsTheQuantisedGridAndTheHeader) {
  const core::TempMap sent = Sample();
  auto received = AsReceived(sent);
  ASSERT_TRUE(received.ok()) << received.status().ToString();
  EXPECT_EQ(received->vehicle_id, "cts2");
  EXPECT_EQ(received->sequence, 7);
  EXPECT_EQ(received->anchor_in_map.x_m, sent.anchor_in_map.x_m);
  EXPECT_EQ(received->anchor_in_map.theta_rad, sent.anchor_in_map.theta_rad);
  EXPECT_EQ(received->start_s, 10.0);
  EXPECT_EQ(received->end_s, 13.0);
  EXPECT_EQ(received->grid.geometry().width(), 150);
  EXPECT_EQ(received->grid.geometry().origin().x_m, -3.0);
  EXPECT_TRUE(received->trajectory_in_temp.empty());  // the trajectory does not travel
  int differ = 0;
  for (size_t i = 0; i < sent.grid.cells().size(); ++i) {
    const float a = sent.grid.cells()[i], b = received->grid.cells()[i];
    EXPECT_LE(std::abs(a - b), 0.5f * core::kLogOddsQuantum + 1e-5f) << i;
    differ += a != b;
  }
  EXPECT_GT(differ, 0);  // it really went through the int8 packing
}

}  // namespace
}  // namespace fleetmap::eval
