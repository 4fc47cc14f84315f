// Open floor: pallets stacked on the floor in blocks (rows of pallet positions, no racks),
// lanes between the blocks, a grid of columns and perhaps one partition wall with wide gates.
#include <cmath>

#include "sim/worldgen/building_style.h"

namespace fleetmap::sim::worldgen {

void DrawBlockStackingHall(FloorPlan& plan, Rng& rng) {
  const double length_m = plan.length_m, width_m = plan.width_m;
  const double t = rng.Uniform(0.25, 0.4);
  plan.AddRectangularEnvelope(t);
  const double margin = rng.Uniform(3.5, 5.0);  // free floor along the walls
  const double lane = rng.Uniform(3.0, 4.5);
  const double pallet_x = rng.Chance(0.5) ? 0.8 : 1.0;  // EUR or industrial pallet width
  constexpr double kPalletDepth = 1.2;
  double partition_x = -1.0;
  if (length_m > 40.0 && rng.Chance(0.6)) {
    partition_x = length_m * rng.Uniform(0.35, 0.65);
    const double gate = rng.Uniform(4.0, 6.0);
    plan.AddWallWithOpenings({partition_x, t}, {partition_x, width_m - t}, rng.Uniform(0.2, 0.3),
                             {{width_m * 0.25, gate}, {width_m * 0.75, gate}});
  }
  for (double y = t + margin; y + 2 * kPalletDepth < width_m - t - margin;) {
    const int deep = rng.Int(2, 4);
    const double y1 = std::min(y + deep * kPalletDepth, width_m - t - margin);
    for (double x = t + margin; x < length_m - t - margin;) {
      const int wide = rng.Int(3, 8);
      const double x1 = std::min(x + wide * pallet_x, length_m - t - margin);
      const bool crosses_partition =
          partition_x > 0 && x < partition_x + lane / 2 && x1 > partition_x - lane / 2;
      if (x1 - x >= 2 * pallet_x && !crosses_partition && !rng.Chance(0.25))
        plan.AddBox("pallet_block", x, y, x1, y1);
      x = x1 + lane;
    }
    y = y1 + lane;
  }
  const double px = rng.Uniform(12.0, 18.0), py = rng.Uniform(12.0, 18.0);
  const double c = rng.Uniform(0.4, 0.6);
  for (double x = px; x < length_m - px / 2; x += px)
    for (double y = py; y < width_m - py / 2; y += py) plan.AddBox("column", x, y, x + c, y + c);
}

}  // namespace fleetmap::sim::worldgen
