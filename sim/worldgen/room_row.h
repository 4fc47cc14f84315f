// A row of rooms along a corridor (offices, wards): partition walls across the row, a door
// in the corridor wall of each room, furniture placed by the caller's style.
#pragma once

#include <functional>
#include <vector>

#include "sim/worldgen/floor_plan.h"
#include "sim/worldgen/random.h"

namespace fleetmap::sim::worldgen {

struct RoomRowOptions {
  double x0_m = 0, x1_m = 0;                  // the row's extent along the corridor
  double corridor_y_m = 0;                    // the corridor wall's centre line
  double far_y_m = 0;                         // the row's far side (an outer wall or another row)
  double wall_m = 0.12;                       // partition and corridor wall thickness
  double min_room_m = 3.0, max_room_m = 6.0;  // room widths along the corridor
  double door_m = 0.9;                        // door width
};

// One room: [x0, x1] along the corridor; y from the corridor wall (y_door) to the far side.
struct Room {
  double x0_m, x1_m, y_door_m, y_far_m;
};

// Draws the corridor wall with a door per room and the partitions; calls `furnish` per room.
void AddRoomRow(FloorPlan& plan, const RoomRowOptions& o, Rng& rng,
                const std::function<void(const Room&)>& furnish);

// Rooms on both sides of corridor `i` of `corridors_y_m` (centre lines across the building,
// ascending, each `corridor_m` wide), between `row.x0_m` and `row.x1_m`: the outer rows reach
// the envelope (its inner faces at y_min_m and y_max_m), rows between two corridors meet back
// to back at a shared wall halfway.
void AddRoomsBesideCorridor(FloorPlan& plan, RoomRowOptions row,
                            const std::vector<double>& corridors_y_m, size_t i, double corridor_m,
                            double y_min_m, double y_max_m, Rng& rng,
                            const std::function<void(const Room&)>& furnish);

}  // namespace fleetmap::sim::worldgen
