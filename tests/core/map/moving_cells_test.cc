#include "core/map/moving_cells.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/map/scan_inserter.h"

namespace fleetmap::core {
namespace {

// One beam along +x from (0.05, 0.05) in a 6 m x 1 m grid of 0.1 m cells.
LaserScan Beam(float range_m) {
  LaserScan s;
  s.angle_min_rad = 0;
  s.angle_increment_rad = 0.01;
  s.range_min_m = 0.05;
  s.range_max_m = 10;
  s.ranges_m = {range_m};
  return s;
}

struct Recorder {
  OccupancyGrid grid{GridGeometry(0.1, 60, 10)};
  MovingCells moving{grid.geometry(), MovingCellOptions()};
  void Insert(float range_m, int times) {
    const LaserScan scan = Beam(range_m);
    const Pose2 pose(0.05, 0.05, 0);
    for (int i = 0; i < times; ++i)
      InsertScan(scan, pose, {}, BeamDirections(scan, 0.0), grid, &moving);
  }
  CellIndex At(double x_m) const { return grid.geometry().WorldToCell({x_m, 0.05}); }
};

// A person at 2 m for a while, then gone: the beam reaches the wall at 5 m through the cell,
// a dozen times (summed evidence near 0: not yet free enough to drop a candidate there).
TEST(MovingCellsTest, ACellOccupiedThenSeenThroughIsReportedFree) {
  Recorder r;
  r.Insert(2.0f, 10);
  r.Insert(5.0f, 12);
  const CellIndex person = r.At(2.05), wall = r.At(5.05);
  EXPECT_TRUE(r.moving.Left(person));
  EXPECT_FALSE(r.moving.Left(wall));
  EXPECT_GT(r.grid.log_odds(person), MovingCellOptions().reported_log_odds);  // summed evidence
  EXPECT_EQ(r.moving.Report(r.grid), 1);
  EXPECT_FLOAT_EQ(r.grid.log_odds(person), MovingCellOptions().reported_log_odds);
  EXPECT_EQ(r.grid.state(wall), CellState::kOccupied);
}

// A pallet that stays is hit every time it is seen: never left, however long the map.
TEST(MovingCellsTest, AnObstacleThatStaysIsNotMoving) {
  Recorder r;
  r.Insert(2.0f, 200);
  EXPECT_FALSE(r.moving.Left(r.At(2.05)));
  EXPECT_EQ(r.moving.Report(r.grid), 0);
  EXPECT_EQ(r.grid.state(r.At(2.05)), CellState::kOccupied);
}

// A single stray return is no obstacle and so nothing that moved; nor is a place seen free
// that was never occupied.
TEST(MovingCellsTest, OneStrayHitOrFreeSpaceIsNotMoving) {
  Recorder r;
  r.Insert(2.0f, 1);
  r.Insert(5.0f, 20);
  EXPECT_FALSE(r.moving.Left(r.At(2.05)));
  EXPECT_FALSE(r.moving.Left(r.At(1.05)));
  EXPECT_EQ(r.moving.Report(r.grid), 0);
}

// Seen occupied again after it was left (something came back): still reported free, since
// whatever stands there has been seen to move.
TEST(MovingCellsTest, OnceLeftAlwaysReported) {
  Recorder r;
  r.Insert(2.0f, 10);
  r.Insert(5.0f, 20);
  r.Insert(2.0f, 10);
  EXPECT_EQ(r.grid.state(r.At(2.05)), CellState::kOccupied);
  EXPECT_EQ(r.moving.Report(r.grid), 1);
  EXPECT_EQ(r.grid.state(r.At(2.05)), CellState::kFree);
}

TEST(MovingCellsTest, DisabledTracksNothing) {
  MovingCellOptions options;
  options.enabled = false;
  OccupancyGrid grid(GridGeometry(0.1, 60, 10));
  MovingCells moving(grid.geometry(), options);
  EXPECT_FALSE(moving.tracking());
  const LaserScan near = Beam(2.0f), far = Beam(5.0f);
  for (int i = 0; i < 10; ++i)
    InsertScan(near, Pose2(0.05, 0.05, 0), {}, BeamDirections(near, 0.0), grid, &moving);
  for (int i = 0; i < 12; ++i)  // as in the first test, where a tracker reports one cell
    InsertScan(far, Pose2(0.05, 0.05, 0), {}, BeamDirections(far, 0.0), grid, &moving);
  EXPECT_EQ(moving.Report(grid), 0);
  EXPECT_GT(grid.log_odds(grid.geometry().WorldToCell({2.05, 0.05})), -2.2f);
}

TEST(MovingCellsTest, OptionsAreValidated) {
  MovingCellOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.left_log_odds = o.occupied_log_odds;
  EXPECT_FALSE(o.Validate().ok());
  o = MovingCellOptions();
  o.reported_log_odds = o.left_log_odds;
  EXPECT_FALSE(o.Validate().ok());
  o = MovingCellOptions();
  o.occupied_log_odds = 0;
  EXPECT_FALSE(o.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::core
