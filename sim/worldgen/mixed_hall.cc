// A hall that is not a rectangle: one end wall slanted, one corner rounded, with racks set at
// an angle, machines, round columns and a curved partition: where line features are few.
#include <algorithm>
#include <cmath>

#include "sim/scenario.h"  // DistanceToPolygon
#include "sim/worldgen/building_style.h"

namespace fleetmap::sim::worldgen {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Footprints placed so far, each as a disc that keeps a lane free around it.
class Placer {
 public:
  Placer(Polyline hall, double lane_m) : hall_(std::move(hall)), lane_m_(lane_m) {}
  // Takes the footprint (centre, radius of its enclosing disc) if it lies inside the hall with
  // a lane to the walls and to everything placed.
  bool TryPlace(const Eigen::Vector2d& c, double radius_m) {
    for (int i = 0; i < 8; ++i) {
      const double a = 2 * M_PI * i / 8;
      if (sim::DistanceToPolygon(
              hall_, c + (radius_m + lane_m_) * Eigen::Vector2d(std::cos(a), std::sin(a))) > 0)
        return false;
    }
    for (const auto& [pc, pr] : placed_)
      if ((pc - c).norm() < pr + radius_m + lane_m_) return false;
    placed_.push_back({c, radius_m});
    return true;
  }

 private:
  Polyline hall_;
  double lane_m_;
  std::vector<std::pair<Eigen::Vector2d, double>> placed_;
};

}  // namespace

void DrawMixedHall(FloorPlan& plan, Rng& rng) {
  const double length_m = plan.length_m, width_m = plan.width_m;
  const double t = rng.Uniform(0.25, 0.4);
  const double slant = rng.Uniform(10.0, 30.0) * kDeg;
  const double r = rng.Uniform(0.2, 0.35) * width_m;
  const double h = t / 2;
  Polyline envelope = {
      {h, h}, {length_m - h, h}, {length_m - h - (width_m - t) * std::tan(slant), width_m - h}};
  for (const Eigen::Vector2d& p : Arc({r, width_m - r}, r - h, 90 * kDeg, 180 * kDeg))
    envelope.push_back(p);
  envelope.push_back({h, h});
  plan.AddWall(envelope, t, /*outer=*/true);

  Placer placer(Polyline(envelope.begin(), envelope.end() - 1), rng.Uniform(2.0, 3.0));
  auto random_point = [&] {
    return Eigen::Vector2d(rng.Uniform(0, length_m), rng.Uniform(0, width_m));
  };
  const int racks = rng.Int(3, 6);
  for (int i = 0, tries = 0; i < racks && tries < 500; ++tries) {
    const double len = rng.Uniform(6.0, 12.0);
    const Eigen::Vector2d c = random_point();
    if (!placer.TryPlace(c, len / 2)) continue;
    plan.AddTurnedBox("rack", c, len, 1.2, rng.Uniform(-35.0, 35.0) * kDeg);
    ++i;
  }
  // A curved partition, an arc of 60 to 120 degrees, placed before the machines: it needs
  // the most room.
  for (int tries = 0; tries < 500; ++tries) {
    const double radius = rng.Uniform(2.5, 5.0);
    const Eigen::Vector2d c = random_point();
    if (!placer.TryPlace(c, radius)) continue;
    const double a0 = rng.Uniform(0.0, 2 * M_PI);
    plan.AddWall(Arc(c, radius, a0, a0 + rng.Uniform(60.0, 120.0) * kDeg), 0.2);
    break;
  }
  const int machines = rng.Int(4, 10);
  for (int i = 0, tries = 0; i < machines && tries < 500; ++tries) {
    const double sx = rng.Uniform(1.5, 4.0), sy = rng.Uniform(1.5, 3.0);
    const Eigen::Vector2d c = random_point();
    if (!placer.TryPlace(c, std::hypot(sx, sy) / 2)) continue;
    plan.AddTurnedBox("machine", c, sx, sy,
                      rng.Chance(0.5) ? 0.0 : rng.Uniform(-20.0, 20.0) * kDeg);
    ++i;
  }
  const double pitch = rng.Uniform(10.0, 12.0);
  const double column_r = rng.Uniform(0.2, 0.3);
  for (double x = pitch; x < length_m; x += pitch)
    for (double y = pitch; y < width_m; y += pitch)
      if (placer.TryPlace({x, y}, column_r)) plan.AddDisc("column", {x, y}, column_r);
}

}  // namespace fleetmap::sim::worldgen
