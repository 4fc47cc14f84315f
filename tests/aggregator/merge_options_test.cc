// MergeOptions: distances in metres turned into cells at the map's resolution, the distance
// of every cell to the nearest wall, and a bad option named by Validate().
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "aggregator/merge.h"

namespace fleetmap::aggregator {
namespace {

TEST(MergeOptionsTest, WallDistancesCountCellsToTheNearestOccupiedOne) {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 6, 4));  // unknown but one wall cell
  grid.SetState({1, 1}, core::CellState::kOccupied);
  const std::vector<uint8_t> d = WallDistances(grid, core::OccupancyThresholds{});
  EXPECT_EQ(d[1 * 6 + 1], 0);
  EXPECT_EQ(d[2 * 6 + 2], 1);  // diagonal neighbour: Chebyshev
  EXPECT_EQ(d[3 * 6 + 5], 4);
  EXPECT_EQ(d[0 * 6 + 0], 1);
  core::OccupancyGrid empty(core::GridGeometry(0.05, 3, 3));
  EXPECT_EQ(WallDistances(empty, core::OccupancyThresholds{})[4], 255);  // no wall at all
}

TEST(MergeOptionsTest, DistancesInMetresBecomeTheNearestWholeCells) {
  EXPECT_EQ(CellsFor(0.10, 0.05), 2);
  EXPECT_EQ(CellsFor(0.10, 0.03), 3);
  EXPECT_EQ(CellsFor(0.10, 0.02), 5);
  EXPECT_EQ(CellsFor(0.10, 0.10), 1);
  EXPECT_EQ(CellsFor(0.05, 0.10), 1);  // a distance > 0 is at least one cell
  EXPECT_EQ(CellsFor(0.0, 0.05), 0);
  const MergeCells c = MergeCellsFor(MergeOptions{}, 0.05);
  EXPECT_EQ(c.static_clearance, 2);  // the defaults at 5 cm are those chosen there in cells
  EXPECT_EQ(c.removal_clearance, 2);
  EXPECT_EQ(c.confirm_radius, 1);
}

// A wall at 2 cm keeps a clearance of 0.10 m, five cells, where nothing is added.
TEST(MergeOptionsTest, TheStaticClearanceIsTheSameDistanceAtAFinerResolution) {
  core::OccupancyGrid fine(core::GridGeometry(0.02, 20, 20));
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x)
      fine.SetState({x, y}, y == 0 ? core::CellState::kOccupied : core::CellState::kFree);
  const std::vector<uint8_t> addable = AddableCells(fine, MergeOptions{});
  EXPECT_EQ(addable[5 * 20 + 10], 0);  // 0.10 m from the wall
  EXPECT_EQ(addable[6 * 20 + 10], 1);  // 0.12 m
}

TEST(MergeOptionsTest, ValidateNamesTheBadField) {
  MergeOptions o;
  o.confirmations = 3;
  EXPECT_NE(o.Validate().message().find("confirmations"), std::string::npos);
  o = {};
  o.remove_max_log_odds = 1;
  EXPECT_NE(o.Validate().message().find("remove_max_log_odds"), std::string::npos);
  o = {};
  o.confirm_max_gap_s = o.confirm_min_gap_s;
  EXPECT_NE(o.Validate().message().find("confirm_max_gap_s"), std::string::npos);
  o = {};
  o.static_clearance_m = 2.0;  // a value in cells where metres are asked
  EXPECT_NE(o.Validate().message().find("static_clearance_m"), std::string::npos);
  o = {};
  o.wall_offset_window_m = -0.1;
  EXPECT_NE(o.Validate().message().find("wall_offset_window_m"), std::string::npos);
  o = MergeOptions();
  o.held_wall_clearance_m = 0.6;
  EXPECT_NE(o.Validate().message().find("held_wall_clearance_m"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::aggregator
