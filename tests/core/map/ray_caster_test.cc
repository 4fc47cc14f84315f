#include "core/map/ray_caster.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/map/occupancy_grid.h"

namespace fleetmap::core {
namespace {

// A free 10 m x 6 m room at 5 cm with one-cell walls around it.
OccupancyGrid Room() {
  OccupancyGrid grid(GridGeometry(0.05, 200, 120));
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 200; ++x)
      grid.SetState({x, y}, (x == 0 || y == 0 || x == 199 || y == 119) ? CellState::kOccupied
                                                                       : CellState::kFree);
  return grid;
}

std::vector<uint8_t> Solid(const OccupancyGrid& g) {
  std::vector<uint8_t> s(g.cells().size());
  for (size_t i = 0; i < s.size(); ++i) s[i] = g.cells()[i] > 0;
  return s;
}

TEST(RayCasterTest, HitsTheWallAtItsInnerFace) {
  const auto room = Room();
  RayCaster caster(room.geometry());
  caster.SetSolid(Solid(room));
  // From (5, 3) straight to +x: the wall cell x = 199 starts at 9.95 m.
  const RayHit hit = caster.Cast({5.0, 3.0}, 0.0, 30.0);
  EXPECT_NEAR(hit.range_m, 4.95, 1e-6);
  EXPECT_EQ(hit.cell, (CellIndex{199, 60}));
  // Diagonal: to the corner region, exact against the geometry of the inner faces.
  const RayHit diag = caster.Cast({5.0, 3.0}, M_PI / 4, 30.0);
  EXPECT_NEAR(diag.range_m, (5.95 - 3.0) * std::sqrt(2.0), 1e-6);
}

TEST(RayCasterTest, MatchesBruteForceMarchingOnRandomRays) {
  auto room = Room();
  for (int x = 80; x < 90; ++x)
    for (int y = 40; y < 45; ++y) room.SetState({x, y}, CellState::kOccupied);
  RayCaster caster(room.geometry());
  caster.SetSolid(Solid(room));
  for (int k = 0; k < 360; k += 7) {
    const double a = k * M_PI / 180.0;
    const RayHit hit = caster.Cast({2.0, 1.5}, a, 30.0);
    // Brute force: march in 1 mm steps.
    double t = 0;
    while (room.log_odds(
               room.geometry().WorldToCell({2.0 + t * std::cos(a), 1.5 + t * std::sin(a)})) <= 0)
      t += 0.001;
    ASSERT_NEAR(hit.range_m, t, 0.0011) << "angle " << k;
  }
}

// A caster whose jumps are capped finds the same cells as one whose are not, and one updated
// around a change casts exactly as one built on the changed cells.
TEST(RayCasterTest, ACappedFieldUpdatedAroundAChangeCastsAsOneBuiltAfresh) {
  auto before = Room();
  for (int x = 80; x < 90; ++x)
    for (int y = 40; y < 45; ++y) before.SetState({x, y}, CellState::kOccupied);
  auto after = before;
  for (int x = 80; x < 90; ++x)
    for (int y = 40; y < 45; ++y) after.SetState({x, y}, CellState::kFree);
  for (int x = 150; x < 160; ++x)
    for (int y = 1; y < 10; ++y) after.SetState({x, y}, CellState::kOccupied);
  RayCaster updated(before.geometry(), 0.5), fresh(after.geometry(), 0.5),
      uncapped(after.geometry());
  updated.SetSolid(Solid(before));
  const CellWindow changed{80, 1, 80, 44};
  std::vector<uint8_t> window_cells;
  for (int y = changed.y0; y < changed.y0 + changed.height; ++y)
    for (int x = changed.x0; x < changed.x0 + changed.width; ++x)
      window_cells.push_back(after.cells()[after.geometry().Index({x, y})] > 0);
  updated.UpdateSolid(changed, window_cells);
  fresh.SetSolid(Solid(after));
  uncapped.SetSolid(Solid(after));
  int rays_changed = 0;
  RayCaster old(before.geometry(), 0.5);
  old.SetSolid(Solid(before));
  for (const Eigen::Vector2d& origin : {Eigen::Vector2d(2.0, 1.5), Eigen::Vector2d(8.0, 4.0)}) {
    for (int k = 0; k < 360; k += 3) {
      const double a = k * M_PI / 180.0;
      const RayHit u = updated.Cast(origin, a, 30.0), f = fresh.Cast(origin, a, 30.0);
      ASSERT_EQ(u.range_m, f.range_m) << k;
      ASSERT_EQ(u.cell, f.cell) << k;
      const RayHit w = uncapped.Cast(origin, a, 30.0);
      ASSERT_EQ(f.cell, w.cell) << k;
      ASSERT_NEAR(f.range_m, w.range_m, 1e-6) << k;
      rays_changed += old.Cast(origin, a, 30.0).cell != f.cell;
    }
  }
  EXPECT_GE(rays_changed, 5) << "the change hides from every ray: the test tests nothing";
}

// Straight down from a point on a cell boundary: cos(270 deg) is -1.8e-16, which in floating
// point never moves the ray off the boundary; it must still reach the wall (and return).
TEST(RayCasterTest, ARayAlongACellBoundaryReachesTheWall) {
  const auto room = Room();
  for (double cap_m : {0.0, 0.5}) {
    RayCaster caster(room.geometry(), cap_m);
    caster.SetSolid(Solid(room));
    const RayHit hit = caster.Cast({2.0, 1.5}, 1.5 * M_PI, 30.0);
    EXPECT_NEAR(hit.range_m, 1.45, 1e-6) << cap_m;
    EXPECT_EQ(hit.cell, (CellIndex{40, 0})) << cap_m;
  }
}

TEST(RayCasterTest, NothingWithinRangeOrOutsideTheGrid) {
  const auto room = Room();
  RayCaster caster(room.geometry());
  caster.SetSolid(Solid(room));
  EXPECT_EQ(caster.Cast({5.0, 3.0}, 0.0, 2.0).range_m, kNoHit);
  RayCaster empty(room.geometry());
  empty.SetSolid(std::vector<uint8_t>(room.cells().size(), 0));
  EXPECT_EQ(empty.Cast({5.0, 3.0}, 0.3, 50.0).range_m, kNoHit);
}

}  // namespace
}  // namespace fleetmap::core
