// Occupancy probability at any point of a grid, bilinearly interpolated between cell centres,
// with its gradient: what Gauss-Newton scan matching descends (hector_slam's OccGridMapUtil).
// Never-observed cells count as probability 0, so unexplored space does not attract points.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/map/occupancy_grid.h"

namespace fleetmap::vehicle_agent {

struct InterpolatedValue {
  double value = 0.0;              // occupancy probability in [0, 1]
  Eigen::Vector2d gradient_per_m;  // d value / d (x, y), per metre in the grid's frame
};

class MapInterpolator {
 public:
  explicit MapInterpolator(const core::OccupancyGrid* grid);  // `grid` outlives this
  // `p` in the frame the grid's geometry is expressed in (origin yaw must be 0).
  InterpolatedValue At(const Eigen::Vector2d& p) const;
  // At(p).value alone (the same number), for searches that need no gradient.
  double Value(const Eigen::Vector2d& p) const;

 private:
  double Probability(int x, int y) const;  // 0 outside the grid
  double FromLogOdds(float log_odds) const;
  struct Corners {
    double fx, fy;              // position between the cell centres, [0, 1)
    double p00, p10, p01, p11;  // probabilities of the four cells around it
  };
  Corners CornersAt(const Eigen::Vector2d& p) const;
  static double Blend(const Corners& c);  // the bilinear value

  const core::OccupancyGrid* grid_;
  // log-odds -> probability, sampled over the grid's clamping range (exp per lookup would be
  // the matcher's hottest cost); shared by every interpolator over the same limits.
  const std::array<float, 1024>* table_;
  float table_min_, table_scale_;
};

// Inline: the matcher calls these a few thousand times per scan, in its innermost loops.
inline double MapInterpolator::Probability(int x, int y) const {
  const core::GridGeometry& g = grid_->geometry();
  if (x < 0 || y < 0 || x >= g.width() || y >= g.height()) return 0.0;
  return FromLogOdds(grid_->cells()[static_cast<size_t>(y) * g.width() + x]);
}

inline double MapInterpolator::FromLogOdds(float l) const {
  if (l == 0.0f) return 0.0;  // never observed
  const int i = static_cast<int>((l - table_min_) * table_scale_ + 0.5f);
  return (*table_)[static_cast<size_t>(std::clamp(i, 0, static_cast<int>(table_->size()) - 1))];
}

inline MapInterpolator::Corners MapInterpolator::CornersAt(const Eigen::Vector2d& p) const {
  const core::GridGeometry& g = grid_->geometry();
  const double res = g.resolution_m();
  // Continuous coordinates of cell centres: cell (i, j) has its centre at (i, j).
  const double u = (p.x() - g.origin().x_m) / res - 0.5;
  const double v = (p.y() - g.origin().y_m) / res - 0.5;
  const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
  Corners c;
  c.fx = u - x0, c.fy = v - y0;
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < g.width() && y0 + 1 < g.height()) {
    // The matcher's common case, all four cells inside: one index, no per-cell bounds checks.
    const float* row = grid_->cells().data() + static_cast<size_t>(y0) * g.width() + x0;
    c.p00 = FromLogOdds(row[0]), c.p10 = FromLogOdds(row[1]);
    c.p01 = FromLogOdds(row[g.width()]), c.p11 = FromLogOdds(row[g.width() + 1]);
  } else {
    c.p00 = Probability(x0, y0), c.p10 = Probability(x0 + 1, y0);
    c.p01 = Probability(x0, y0 + 1), c.p11 = Probability(x0 + 1, y0 + 1);
  }
  return c;
}

inline double MapInterpolator::Blend(const Corners& c) {
  return (1 - c.fy) * ((1 - c.fx) * c.p00 + c.fx * c.p10) +
         c.fy * ((1 - c.fx) * c.p01 + c.fx * c.p11);
}

inline double MapInterpolator::Value(const Eigen::Vector2d& p) const { return Blend(CornersAt(p)); }

inline InterpolatedValue MapInterpolator::At(const Eigen::Vector2d& p) const {
  const Corners c = CornersAt(p);
  const double fx = c.fx, fy = c.fy;
  InterpolatedValue out;
  out.value = Blend(c);
  out.gradient_per_m = Eigen::Vector2d((1 - fy) * (c.p10 - c.p00) + fy * (c.p11 - c.p01),
                                       (1 - fx) * (c.p01 - c.p00) + fx * (c.p11 - c.p10)) /
                       grid_->geometry().resolution_m();
  return out;
}

}  // namespace fleetmap::vehicle_agent
