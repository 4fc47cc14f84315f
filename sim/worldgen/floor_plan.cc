#include "sim/worldgen/floor_plan.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::sim::worldgen {

void FloorPlan::AddWall(Polyline points_m, double thickness_m, bool outer) {
  walls.push_back({std::move(points_m), thickness_m, outer});
}

void FloorPlan::AddWallWithOpenings(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                    double thickness_m,
                                    std::vector<std::pair<double, double>> openings) {
  const double length = (b - a).norm();
  if (length <= 0) return;
  const Eigen::Vector2d dir = (b - a) / length;
  std::sort(openings.begin(), openings.end());
  double from = 0.0;
  for (const auto& [centre, width] : openings) {
    const double lo = centre - width / 2, hi = centre + width / 2;
    if (lo < from + thickness_m || hi > length - thickness_m) continue;  // does not fit
    AddWall({a + dir * from, a + dir * lo}, thickness_m);
    from = hi;
  }
  AddWall({a + dir * from, b}, thickness_m);
}

void FloorPlan::AddBox(const std::string& kind, double x0, double y0, double x1, double y1) {
  solids.push_back({kind, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}});
}

void FloorPlan::AddTurnedBox(const std::string& kind, const Eigen::Vector2d& c, double sx,
                             double sy, double yaw_rad) {
  const Eigen::Vector2d u(std::cos(yaw_rad), std::sin(yaw_rad));
  const Eigen::Vector2d v(-u.y(), u.x());
  const Eigen::Vector2d hx = u * (sx / 2), hy = v * (sy / 2);
  solids.push_back({kind, {c - hx - hy, c + hx - hy, c + hx + hy, c - hx + hy}});
}

void FloorPlan::AddDisc(const std::string& kind, const Eigen::Vector2d& c, double radius_m) {
  Polyline p;
  for (int i = 0; i < 16; ++i) {
    const double a = 2 * M_PI * i / 16;
    p.push_back(c + radius_m * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  solids.push_back({kind, std::move(p)});
}

void FloorPlan::AddRectangularEnvelope(double t) {
  const double h = t / 2;
  AddWall({{h, h}, {length_m - h, h}, {length_m - h, width_m - h}, {h, width_m - h}, {h, h}}, t,
          /*outer=*/true);
}

Polyline Arc(const Eigen::Vector2d& c, double r, double a0, double a1, double step_m) {
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(a1 - a0) * r / step_m)) + 1);
  Polyline p;
  for (int i = 0; i < n; ++i) {
    const double a = a0 + (a1 - a0) * i / (n - 1);
    p.push_back(c + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return p;
}

}  // namespace fleetmap::sim::worldgen
