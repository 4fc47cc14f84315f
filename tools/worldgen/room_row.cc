#include "tools/worldgen/room_row.h"

#include <algorithm>

namespace fleetmap::worldgen {

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

}  // namespace fleetmap::worldgen
