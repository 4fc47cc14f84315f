#include "core/map/scan_inserter.h"

#include <cassert>
#include <cmath>
#include <limits>

namespace fleetmap::core {
namespace {

// Clips the segment a->b (continuous cell coordinates) to the grid's rectangle (Liang and
// Barsky); false when it misses the grid entirely.
bool ClipToGrid(const GridGeometry& g, Eigen::Vector2d& a, Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0, t1 = 1.0;
  const double lo[2] = {0.0, 0.0}, hi[2] = {g.width() - 1e-9, g.height() - 1e-9};
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(d[axis]) < 1e-15) {
      if (a[axis] < lo[axis] || a[axis] > hi[axis]) return false;
      continue;
    }
    double ta = (lo[axis] - a[axis]) / d[axis], tb = (hi[axis] - a[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  const Eigen::Vector2d start = a;
  a = start + t0 * d;
  b = start + t1 * d;
  return true;
}

// Walks the cells from `from` towards `to` (exclusive), in continuous cell coordinates,
// calling fn(cell) for each cell inside the grid (Amanatides and Woo). The segment is clipped
// to the grid first, so the part of a beam outside the grid costs nothing.
template <typename Fn>
int WalkCells(const GridGeometry& g, Eigen::Vector2d from, Eigen::Vector2d to, Fn fn) {
  const Eigen::Vector2d original_to = to;
  if (!ClipToGrid(g, from, to)) return 0;
  // A clipped end is not the beam's end: its cell is crossed too, so step just past it.
  if ((to - original_to).squaredNorm() > 1e-18) to += (to - from).normalized() * 1e-6;
  const Eigen::Vector2d d = to - from;
  const double length = d.norm();
  if (length < 1e-12) return 0;
  const Eigen::Vector2d dir = d / length;
  int x = int(std::floor(from.x())), y = int(std::floor(from.y()));
  const int end_x = int(std::floor(to.x())), end_y = int(std::floor(to.y()));
  const int step_x = dir.x() > 0 ? 1 : -1, step_y = dir.y() > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  double t_max_x = dir.x() != 0 ? ((step_x > 0 ? x + 1 : x) - from.x()) / dir.x() : inf;
  double t_max_y = dir.y() != 0 ? ((step_y > 0 ? y + 1 : y) - from.y()) / dir.y() : inf;
  const double t_dx = dir.x() != 0 ? std::abs(1.0 / dir.x()) : inf;
  const double t_dy = dir.y() != 0 ? std::abs(1.0 / dir.y()) : inf;
  int visited = 0;
  // A beam crosses at most |dx| + |dy| + 2 cells; the bound guards against rounding loops.
  const int max_steps = int(std::abs(d.x()) + std::abs(d.y())) + 2;
  for (int i = 0; i < max_steps && !(x == end_x && y == end_y); ++i) {
    if (g.Contains(CellIndex{x, y})) {
      fn(CellIndex{x, y});
      ++visited;
    }
    if (t_max_x < t_max_y) {
      t_max_x += t_dx;
      x += step_x;
    } else {
      t_max_y += t_dy;
      y += step_y;
    }
  }
  return visited;
}

}  // namespace

Status ScanInsertOptions::Validate() const {
  if (!(hit_log_odds > 0 && miss_log_odds < 0 && max_range_m > 0 && no_return_free_m >= 0 &&
        beam_step >= 1)) {
    return InvalidArgument("scan insert options need hit > 0, miss < 0, max range > 0, step >= 1");
  }
  return OkStatus();
}

std::vector<Eigen::Vector2d> BeamDirections(const LaserScan& scan, double theta_rad) {
  std::vector<Eigen::Vector2d> directions(scan.size());
  for (size_t i = 0; i < scan.size(); ++i) {
    const double a = theta_rad + scan.angle(i);
    directions[i] = Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  return directions;
}

InsertStats InsertScan(const LaserScan& scan, const Pose2& scanner_in_grid,
                       const ScanInsertOptions& options, OccupancyGrid& grid) {
  return InsertScan(scan, scanner_in_grid, options, BeamDirections(scan, scanner_in_grid.theta_rad),
                    grid);
}

InsertStats InsertScan(const LaserScan& scan, const Pose2& scanner_in_grid,
                       const ScanInsertOptions& options,
                       const std::vector<Eigen::Vector2d>& beam_directions, OccupancyGrid& grid,
                       MovingCells* moving) {
  assert(beam_directions.size() == scan.size());
  if (moving && !moving->tracking()) moving = nullptr;
  auto add = [&](const CellIndex& c, float delta) {
    grid.AddLogOdds(c, delta);
    if (moving) moving->Observe(c, grid.log_odds(c));
  };
  const GridGeometry& g = grid.geometry();
  InsertStats stats;
  const Eigen::Vector2d origin = g.WorldToGrid(scanner_in_grid.translation());
  for (size_t i = 0; i < scan.size(); i += static_cast<size_t>(options.beam_step)) {
    const bool valid = scan.IsValidReturn(i) && scan.ranges_m[i] <= options.max_range_m;
    const double range = valid ? scan.ranges_m[i] : options.no_return_free_m;
    const bool no_return = !valid && !std::isnan(scan.ranges_m[i]) &&
                           (std::isinf(scan.ranges_m[i]) || scan.ranges_m[i] >= scan.range_max_m);
    if (!valid && !(no_return && options.no_return_free_m > 0)) {
      ++stats.skipped;
      continue;
    }
    const Eigen::Vector2d end =
        g.WorldToGrid(scanner_in_grid.translation() + range * beam_directions[i]);
    stats.cells_missed +=
        WalkCells(g, origin, end, [&](const CellIndex& c) { add(c, options.miss_log_odds); });
    if (!valid) continue;
    const CellIndex hit{int(std::floor(end.x())), int(std::floor(end.y()))};
    if (g.Contains(hit)) {
      add(hit, options.hit_log_odds);
      ++stats.hits;
    } else {
      ++stats.skipped;
    }
  }
  return stats;
}

}  // namespace fleetmap::core
