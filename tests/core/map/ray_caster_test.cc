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
