#include "vehicle_agent/map_interpolator.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::vehicle_agent {

namespace {

using Table = std::array<float, 1024>;

Table MakeTable(float min, float scale) {
  Table t;
  for (size_t i = 0; i < t.size(); ++i) {
    t[i] = static_cast<float>(core::LogOddsToProbability(min + i / scale));
  }
  return t;
}

}  // namespace

MapInterpolator::MapInterpolator(const core::OccupancyGrid* grid) : grid_(grid) {
  const core::LogOddsLimits& l = grid->limits();
  table_min_ = l.min_log_odds;
  table_scale_ = (Table().size() - 1) / (l.max_log_odds - l.min_log_odds);
  // The default limits' table is built once; other limits (rare) get their own, kept per
  // thread so that concurrent matchers never share a mutable cache.
  static const core::LogOddsLimits kDefault;
  static const Table kDefaultTable =
      MakeTable(kDefault.min_log_odds,
                (Table().size() - 1) / (kDefault.max_log_odds - kDefault.min_log_odds));
  if (l.min_log_odds == kDefault.min_log_odds && l.max_log_odds == kDefault.max_log_odds) {
    table_ = &kDefaultTable;
  } else {
    thread_local Table custom;
    custom = MakeTable(table_min_, table_scale_);
    table_ = &custom;
  }
}

double MapInterpolator::Probability(int x, int y) const {
  const core::GridGeometry& g = grid_->geometry();
  if (x < 0 || y < 0 || x >= g.width() || y >= g.height()) return 0.0;
  return FromLogOdds(grid_->cells()[static_cast<size_t>(y) * g.width() + x]);
}

double MapInterpolator::FromLogOdds(float l) const {
  if (l == 0.0f) return 0.0;  // never observed
  const int i = static_cast<int>((l - table_min_) * table_scale_ + 0.5f);
  return (*table_)[static_cast<size_t>(std::clamp(i, 0, static_cast<int>(table_->size()) - 1))];
}

MapInterpolator::Corners MapInterpolator::CornersAt(const Eigen::Vector2d& p) const {
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

double MapInterpolator::Value(const Eigen::Vector2d& p) const {
  const Corners c = CornersAt(p);
  return (1 - c.fy) * ((1 - c.fx) * c.p00 + c.fx * c.p10) +
         c.fy * ((1 - c.fx) * c.p01 + c.fx * c.p11);
}

InterpolatedValue MapInterpolator::At(const Eigen::Vector2d& p) const {
  const Corners c = CornersAt(p);
  const double fx = c.fx, fy = c.fy;
  InterpolatedValue out;
  out.value = (1 - fy) * ((1 - fx) * c.p00 + fx * c.p10) + fy * ((1 - fx) * c.p01 + fx * c.p11);
  out.gradient_per_m = Eigen::Vector2d((1 - fy) * (c.p10 - c.p00) + fy * (c.p11 - c.p01),
                                       (1 - fx) * (c.p01 - c.p00) + fx * (c.p11 - c.p10)) /
                       grid_->geometry().resolution_m();
  return out;
}

}  // namespace fleetmap::vehicle_agent
