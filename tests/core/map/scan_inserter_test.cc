#include "core/map/scan_inserter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/map/temp_map.h"

namespace fleetmap::core {
namespace {

// A 4-beam scan: +x at 2 m, +y at 1 m, -x no return, -y NaN.
LaserScan Cross() {
  LaserScan s;
  s.angle_min_rad = 0;
  s.angle_increment_rad = M_PI / 2;
  s.range_min_m = 0.05;
  s.range_max_m = 10;
  s.ranges_m = {2.0f, 1.0f, INFINITY, NAN};
  return s;
}

TEST(ScanInserterTest, HitsAndFreeSpaceAlongEachBeam) {
  OccupancyGrid grid(GridGeometry(0.1, 60, 60, Pose2(-3, -3, 0)));
  const InsertStats stats = InsertScan(Cross(), Pose2(0.05, 0.05, 0), {}, grid);
  EXPECT_EQ(stats.hits, 2);
  EXPECT_EQ(stats.skipped, 2);
  const GridGeometry& g = grid.geometry();
  EXPECT_EQ(grid.state(g.WorldToCell({2.05, 0.05})), CellState::kOccupied);
  EXPECT_EQ(grid.state(g.WorldToCell({0.05, 1.05})), CellState::kOccupied);
  // One miss (-0.405) is not yet free under map_server thresholds, but it is evidence.
  EXPECT_FLOAT_EQ(grid.log_odds(g.WorldToCell({1.0, 0.05})), -0.405f);
  EXPECT_EQ(grid.log_odds(g.WorldToCell({-1.0, 0.05})), 0.0f);  // no return: nothing
  EXPECT_EQ(grid.log_odds(g.WorldToCell({2.55, 0.05})), 0.0f);  // behind the hit
  EXPECT_EQ(stats.cells_missed, 20 + 10);                       // cells crossed before each hit
}

TEST(ScanInserterTest, NoReturnClearsOnlyWhenAsked) {
  OccupancyGrid grid(GridGeometry(0.1, 60, 60, Pose2(-3, -3, 0)));
  ScanInsertOptions options;
  options.no_return_free_m = 1.5;
  InsertScan(Cross(), Pose2(0.05, 0.05, 0), options, grid);
  EXPECT_LT(grid.log_odds(grid.geometry().WorldToCell({-1.0, 0.05})), 0.0f);
  EXPECT_EQ(grid.log_odds(grid.geometry().WorldToCell({-2.0, 0.05})), 0.0f);
}

TEST(ScanInserterTest, BeamsAreClippedToTheGrid) {
  OccupancyGrid grid(GridGeometry(0.1, 10, 10));  // 1 m x 1 m
  const InsertStats stats = InsertScan(Cross(), Pose2(0.55, 0.55, 0), {}, grid);
  EXPECT_EQ(stats.hits, 0);  // both returns lie outside
  EXPECT_GT(stats.cells_missed, 0);
  EXPECT_EQ(grid.CountState(CellState::kOccupied), 0);
}

TEST(ScanInserterTest, RepeatedScansConvergeToTheTruth) {
  OccupancyGrid grid(GridGeometry(0.1, 60, 60, Pose2(-3, -3, 0)));
  for (int i = 0; i < 10; ++i) InsertScan(Cross(), Pose2(0.05, 0.05, 0), {}, grid);
  EXPECT_EQ(grid.state(grid.geometry().WorldToCell({1.0, 0.05})), CellState::kFree);
  EXPECT_EQ(grid.state(grid.geometry().WorldToCell({2.05, 0.05})), CellState::kOccupied);
}

TEST(TempMapTest, PlacedGeometryComposesCorrectionAnchorAndOrigin) {
  TempMap m;
  m.vehicle_id = "v";
  m.grid = OccupancyGrid(GridGeometry(0.05, 40, 40, Pose2(-1, -1, 0)));
  m.anchor_in_map = Pose2(10, 5, M_PI / 2);
  const GridGeometry placed = m.PlacedGeometry();
  // The temp frame's point (1, 0) is 1 m ahead of the vehicle: (10, 6) in the map.
  const Eigen::Vector2d c = placed.CellCenter(m.grid.geometry().WorldToCell({1.0, 0.0}));
  EXPECT_NEAR(c.x(), 10.0 - 0.025, 1e-9);
  EXPECT_NEAR(c.y(), 6.0 + 0.025, 1e-9);
  const GridGeometry shifted = m.PlacedGeometry(Pose2(0.5, 0, 0));
  EXPECT_NEAR(shifted.origin().x_m, placed.origin().x_m + 0.5, 1e-9);
  EXPECT_TRUE(m.Validate().ok());
  m.end_s = -1;
  EXPECT_FALSE(m.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::core
