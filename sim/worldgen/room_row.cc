#include "sim/worldgen/room_row.h"

#include <algorithm>

namespace fleetmap::sim::worldgen {

void AddRoomRow(FloorPlan& plan, const RoomRowOptions& o, Rng& rng,
                const std::function<void(const Room&)>& furnish) {
  std::vector<std::pair<double, double>> doors;
  double x = o.x0_m;
  while (o.x1_m - x >= o.min_room_m) {
    double w = rng.Uniform(o.min_room_m, o.max_room_m);
    if (o.x1_m - (x + w) < o.min_room_m) w = o.x1_m - x;  // the last room takes the rest
    const double door_at =
        rng.Uniform(x + o.wall_m + o.door_m / 2 + 0.2, x + w - o.wall_m - o.door_m / 2 - 0.2);
    doors.push_back({door_at - o.x0_m, o.door_m});
    if (x + w < o.x1_m - 1e-6)
      plan.AddWall({{x + w, o.corridor_y_m}, {x + w, o.far_y_m}}, o.wall_m);
    furnish({x, x + w, o.corridor_y_m, o.far_y_m});
    x += w;
  }
  plan.AddWallWithOpenings({o.x0_m, o.corridor_y_m}, {o.x1_m, o.corridor_y_m}, o.wall_m, doors);
  // The row's ends: closed towards whatever lies beyond (a lobby, an open-plan area).
  plan.AddWall({{o.x0_m, o.corridor_y_m}, {o.x0_m, o.far_y_m}}, o.wall_m);
  plan.AddWall({{o.x1_m, o.corridor_y_m}, {o.x1_m, o.far_y_m}}, o.wall_m);
}

void AddRoomsBesideCorridor(FloorPlan& plan, RoomRowOptions row,
                            const std::vector<double>& corridors_y_m, size_t i, double corridor_m,
                            double y_min_m, double y_max_m, Rng& rng,
                            const std::function<void(const Room&)>& furnish) {
  const std::vector<double>& c = corridors_y_m;
  const double below_far = i == 0 ? y_min_m : (c[i - 1] + c[i]) / 2;
  const double above_far = i + 1 == c.size() ? y_max_m : (c[i] + c[i + 1]) / 2;
  row.corridor_y_m = c[i] - corridor_m / 2;
  row.far_y_m = below_far;
  AddRoomRow(plan, row, rng, furnish);
  if (i > 0) plan.AddWall({{row.x0_m, below_far}, {row.x1_m, below_far}}, row.wall_m);
  row.corridor_y_m = c[i] + corridor_m / 2;
  row.far_y_m = above_far;
  AddRoomRow(plan, row, rng, furnish);
}

}  // namespace fleetmap::sim::worldgen
