// Long corridors 2.4 to 3 m wide with ward rooms on both sides (wide doors, one or two beds),
// a widened stretch with a nurse station in the middle, carts parked in the corridors and a
// lobby with a reception desk at one end.
#include <cmath>

#include "sim/worldgen/building_style.h"
#include "sim/worldgen/room_row.h"

namespace fleetmap::sim::worldgen {
namespace {

void FurnishWard(FloorPlan& plan, const Room& r, Rng& rng) {
  const double dir = r.y_far_m > r.y_door_m ? 1.0 : -1.0;
  constexpr double kBedX = 1.0, kBedY = 2.1;
  const double bed_y = r.y_far_m - dir * (0.2 + kBedY / 2);
  const double w = r.x1_m - r.x0_m;
  const int beds = w >= 4.2 && rng.Chance(0.6) ? 2 : 1;
  for (int b = 0; b < beds; ++b) {
    const double cx = r.x0_m + w * (b + 1) / (beds + 1);
    plan.AddTurnedBox("bed", {cx, bed_y}, kBedX, kBedY, 0.0);
  }
  if (rng.Chance(0.5))
    plan.AddTurnedBox("cabinet", {r.x1_m - 0.45, r.y_door_m + dir * 1.8}, 0.5, 0.6, 0.0);
}

}  // namespace

void DrawHospital(FloorPlan& plan, Rng& rng) {
  const double length_m = plan.length_m, width_m = plan.width_m;
  const double t = rng.Uniform(0.25, 0.35);
  plan.AddRectangularEnvelope(t);
  const double lobby = rng.Uniform(6.0, 10.0);
  const double c = rng.Uniform(2.4, 3.0);
  const double station_x = length_m * rng.Uniform(0.4, 0.6);
  const double station_gap = 6.0;
  RoomRowOptions row;
  row.wall_m = 0.15;
  row.min_room_m = 3.5;
  row.max_room_m = 4.5;
  row.door_m = rng.Uniform(1.2, 1.4);
  auto furnish = [&](const Room& r) { FurnishWard(plan, r, rng); };
  std::vector<double> corridors;
  if (width_m < 26.0) {
    corridors = {width_m * rng.Uniform(0.45, 0.55)};
  } else {
    corridors = {width_m / 3, 2 * width_m / 3};
  }
  const std::pair<double, double> runs[] = {{t + lobby, station_x - station_gap / 2},
                                            {station_x + station_gap / 2, length_m - t}};
  for (size_t i = 0; i < corridors.size(); ++i) {
    for (const auto& [x0, x1] : runs) {
      if (x1 - x0 < row.min_room_m) continue;
      row.x0_m = x0;
      row.x1_m = x1;
      AddRoomsBesideCorridor(plan, row, corridors, i, c, t, width_m - t, rng, furnish);
    }
    // The nurse station stands in the widened stretch, beside the corridor.
    plan.AddTurnedBox("desk", {station_x, corridors[i] + c / 2 + 1.2}, 3.0, 1.0, 0.0);
    // Carts along the corridor walls, clear of the doors' middle by chance only.
    for (double x = t + lobby + 5.0; x < length_m - t - 5.0; x += rng.Uniform(8.0, 16.0)) {
      if (std::abs(x - station_x) < station_gap) continue;
      const double side = rng.Chance(0.5) ? -1.0 : 1.0;
      plan.AddTurnedBox("cart", {x, corridors[i] + side * (c / 2 - 0.4)}, 0.6, 0.5, 0.0);
    }
  }
  plan.AddTurnedBox("desk", {t + lobby / 2, width_m * 0.5}, 1.0, 3.0, 0.0);
}

}  // namespace fleetmap::sim::worldgen
