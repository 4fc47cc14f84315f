// Rack rows along the building's length: single rows against the aisles at the ends of the
// pattern, back-to-back double rows between, cut into segments by cross aisles; columns in the
// double rows and along the walls; a free dock zone along one side for staging.
#include <algorithm>
#include <cmath>

#include "sim/worldgen/building_style.h"

namespace fleetmap::sim::worldgen {

void DrawRackedWarehouse(FloorPlan& plan, Rng& rng) {
  const double length_m = plan.length_m, width_m = plan.width_m;
  const double t = rng.Uniform(0.25, 0.4);
  plan.AddRectangularEnvelope(t);
  constexpr double kRackDepth = 1.2;
  const double dock = rng.Uniform(5.0, 9.0);
  const double end_aisle = rng.Uniform(3.0, 4.0);
  const double top_aisle = rng.Uniform(2.5, 4.0);
  const double aisle = rng.Uniform(2.5, 4.0);
  const double segment = rng.Uniform(20.0, 30.0);
  const double cross = rng.Uniform(3.0, 4.0);
  const double pitch = rng.Uniform(10.0, 14.0);
  const double column = rng.Uniform(0.35, 0.6);

  // Rows (y0, y1, double?) from the dock to the top aisle.
  struct Row {
    double y0, y1;
    bool twin;
  };
  std::vector<Row> rows;
  double y = t + dock;
  const double y_end = width_m - t - top_aisle;
  for (bool first = true;; first = false) {
    const double depth = first ? kRackDepth : 2 * kRackDepth;
    if (y + depth > y_end) {
      if (y + kRackDepth <= y_end) rows.push_back({y, y + kRackDepth, false});
      break;
    }
    rows.push_back({y, y + depth, !first});
    y += depth + aisle;
  }
  const double x0 = t + end_aisle, x1 = length_m - t - end_aisle;
  const int segments =
      std::max(1, static_cast<int>(std::lround((x1 - x0 + cross) / (segment + cross))));
  const double seg_len = (x1 - x0 - (segments - 1) * cross) / segments;
  for (const Row& r : rows) {
    for (int s = 0; s < segments; ++s) {
      const double sx = x0 + s * (seg_len + cross);
      plan.AddBox("rack", sx, r.y0, sx + seg_len, r.y1);
      if (!r.twin) continue;
      // Columns stand in the double rows' flue, where the racks hide them from the aisles.
      for (double cx = sx + pitch / 2; cx < sx + seg_len - column; cx += pitch)
        plan.AddBox("column", cx - column / 2, (r.y0 + r.y1) / 2 - column / 2, cx + column / 2,
                    (r.y0 + r.y1) / 2 + column / 2);
    }
  }
  // Pilasters along the long walls.
  for (double cx = t + pitch; cx < length_m - t - pitch / 2; cx += pitch) {
    plan.AddBox("column", cx - column / 2, t, cx + column / 2, t + column / 2);
    plan.AddBox("column", cx - column / 2, width_m - t - column / 2, cx + column / 2, width_m - t);
  }
  // A few pallets waiting in the dock zone.
  const int waiting = rng.Int(1, 4);
  for (int i = 0; i < waiting; ++i) {
    const double px = rng.Uniform(t + 4.0, length_m - t - 4.0);
    plan.AddBox("pallet", px, t + 0.6, px + 1.2, t + 1.4);
  }
}

}  // namespace fleetmap::sim::worldgen
