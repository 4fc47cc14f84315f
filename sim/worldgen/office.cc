// Corridors along the building with rooms on both sides (a door each, desks, tables,
// cabinets), a lobby at one end and, in larger buildings, an open-plan area with desk islands
// at the other.
#include <cmath>

#include "sim/worldgen/building_style.h"
#include "sim/worldgen/room_row.h"

namespace fleetmap::sim::worldgen {
namespace {

void FurnishOffice(FloorPlan& plan, const Room& r, Rng& rng) {
  const double dir = r.y_far_m > r.y_door_m ? 1.0 : -1.0;
  const double depth = std::abs(r.y_far_m - r.y_door_m);
  const double cx = (r.x0_m + r.x1_m) / 2;
  const double desk_y = r.y_far_m - dir * (0.25 + 0.375);
  plan.AddTurnedBox("desk", {cx, desk_y}, rng.Uniform(1.4, 1.8), 0.75, 0.0);
  if (depth >= 4.5 && rng.Chance(0.4))
    plan.AddDisc("table", {cx, (r.y_door_m + r.y_far_m) / 2}, rng.Uniform(0.45, 0.6));
  if (rng.Chance(0.5))
    plan.AddTurnedBox("cabinet", {r.x0_m + 0.4, r.y_far_m - dir * 1.6}, 0.45, 0.9, 0.0);
}

void AddDeskIslands(FloorPlan& plan, double x0, double x1, double y0, double y1, Rng& rng) {
  const double lane = rng.Uniform(1.8, 2.4);
  constexpr double kIslandX = 3.2, kIslandY = 1.6;  // four desks of 1.6 m x 0.8 m
  for (double y = y0 + lane; y + kIslandY < y1 - lane; y += kIslandY + lane)
    for (double x = x0 + lane; x + kIslandX < x1 - lane; x += kIslandX + lane)
      if (!rng.Chance(0.2)) plan.AddBox("desk", x, y, x + kIslandX, y + kIslandY);
}

}  // namespace

void DrawOffice(FloorPlan& plan, Rng& rng) {
  const double length_m = plan.length_m, width_m = plan.width_m;
  const double t = rng.Uniform(0.2, 0.35);
  plan.AddRectangularEnvelope(t);
  const double lobby = rng.Uniform(4.0, 8.0);
  const double open_plan = length_m > 35.0 && rng.Chance(0.6) ? rng.Uniform(8.0, 15.0) : 0.0;
  const double c = rng.Uniform(1.6, 2.4);
  RoomRowOptions row;
  row.x0_m = t + lobby;
  row.x1_m = length_m - t - open_plan;
  row.wall_m = rng.Uniform(0.1, 0.15);
  row.door_m = rng.Uniform(0.9, 1.0);
  auto furnish = [&](const Room& r) { FurnishOffice(plan, r, rng); };
  // One corridor in a narrow building, two in a wide one (rooms back to back between them).
  std::vector<double> corridors;
  if (width_m < 18.0) {
    corridors = {width_m * rng.Uniform(0.42, 0.58)};
  } else {
    corridors = {width_m / 3, 2 * width_m / 3};
  }
  for (size_t i = 0; i < corridors.size(); ++i)
    AddRoomsBesideCorridor(plan, row, corridors, i, c, t, width_m - t, rng, furnish);
  if (open_plan > 0)
    AddDeskIslands(plan, length_m - t - open_plan, length_m - t, t, width_m - t, rng);
  // A reception desk in the lobby.
  plan.AddTurnedBox("desk", {t + lobby / 2, width_m * rng.Uniform(0.2, 0.3)}, 0.8, 2.4, 0.0);
}

}  // namespace fleetmap::sim::worldgen
