#include "aggregator/alignment/placement.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace fleetmap::aggregator {
namespace {

using core::GridGeometry;

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

core::Status CheckSize(const GridGeometry& g, const GridGeometry& s, const PlacementOptions& o) {
  if (std::abs(g.resolution_m() - s.resolution_m()) > o.resolution_tolerance * s.resolution_m()) {
    return core::InvalidArgument("temporary map resolution " + Num(g.resolution_m()) +
                                 " m differs from the static map's " + Num(s.resolution_m()) +
                                 " m");
  }
  if (g.num_cells() > o.max_cells || g.width() * g.resolution_m() > o.max_extent_m ||
      g.height() * g.resolution_m() > o.max_extent_m) {
    return core::OutOfRange("temporary map of " + g.ToString() + " exceeds the limits of " +
                            std::to_string(o.max_cells) + " cells and " + Num(o.max_extent_m) +
                            " m a side");
  }
  return core::OkStatus();
}

core::Status CheckValues(const core::TempMap& map) {
  for (float l : map.grid.cells())
    if (!std::isfinite(l)) return core::InvalidArgument("temporary map holds a non-finite cell");
  for (const core::TimedPose& p : map.trajectory_in_temp) {
    if (!p.pose.IsFinite() || !std::isfinite(p.stamp_s))
      return core::InvalidArgument("temporary map trajectory holds a non-finite pose");
  }
  return core::OkStatus();
}

core::Status CheckInside(const core::TempMap& map, const GridGeometry& s,
                         const PlacementOptions& o) {
  const GridGeometry placed = map.PlacedGeometry();
  // Temporary cell centre -> static grid coordinates is affine.
  const Eigen::Vector2d base = s.WorldToGrid(placed.CellCenter({0, 0}));
  const Eigen::Vector2d step_x = s.WorldToGrid(placed.CellCenter({1, 0})) - base;
  const Eigen::Vector2d step_y = s.WorldToGrid(placed.CellCenter({0, 1})) - base;
  int64_t observed = 0, inside = 0;
  const int w = placed.width();
  for (size_t i = 0; i < map.grid.cells().size(); ++i) {
    if (map.grid.cells()[i] == 0.0f) continue;
    ++observed;
    const Eigen::Vector2d g = base + double(i % w) * step_x + double(i / w) * step_y;
    inside += g.x() >= 0 && g.y() >= 0 && g.x() < s.width() && g.y() < s.height();
  }
  if (observed == 0) return core::InvalidArgument("temporary map observed nothing");
  const double fraction = double(inside) / double(observed);
  if (fraction < o.min_inside_fraction) {
    return core::OutOfRange("temporary map lies outside the static map: " + Num(100 * fraction) +
                            "% of its observed cells inside, " + Num(100 * o.min_inside_fraction) +
                            "% needed");
  }
  return core::OkStatus();
}

}  // namespace

core::Status PlacementOptions::Validate() const {
  if (!(resolution_tolerance >= 0 && resolution_tolerance < 0.5))
    return core::InvalidArgument("placement.resolution_tolerance must be in [0, 0.5)");
  if (max_cells < 1) return core::InvalidArgument("placement.max_cells must be >= 1");
  if (!(max_extent_m > 0)) return core::InvalidArgument("placement.max_extent_m must be > 0");
  if (!(min_inside_fraction >= 0 && min_inside_fraction <= 1))
    return core::InvalidArgument("placement.min_inside_fraction must be in [0, 1]");
  return core::OkStatus();
}

core::Status CheckTempMap(const core::TempMap& map, const GridGeometry& static_geometry,
                          const PlacementOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(map.Validate());
  FLEETMAP_RETURN_IF_ERROR(CheckSize(map.grid.geometry(), static_geometry, options));
  if (map.grid.cells().size() != static_cast<size_t>(map.grid.geometry().num_cells()))
    return core::InvalidArgument("temporary map cells do not match its geometry");
  FLEETMAP_RETURN_IF_ERROR(CheckValues(map));
  return CheckInside(map, static_geometry, options);
}

PlacedEvidence PlaceEvidence(const core::TempMap& map, const core::Pose2& correction,
                             const GridGeometry& s) {
  const GridGeometry placed = map.PlacedGeometry(correction);
  // The window: the static cells under the placed grid's four corners, clipped.
  int x0 = s.width(), y0 = s.height(), x1 = -1, y1 = -1;
  for (double cx : {0.0, double(placed.width())}) {
    for (double cy : {0.0, double(placed.height())}) {
      const Eigen::Vector2d corner =
          placed.origin().Apply(Eigen::Vector2d(cx, cy) * placed.resolution_m());
      const core::CellIndex c = s.WorldToCell(corner);
      x0 = std::min(x0, c.x), y0 = std::min(y0, c.y), x1 = std::max(x1, c.x),
      y1 = std::max(y1, c.y);
    }
  }
  x0 = std::max(x0, 0), y0 = std::max(y0, 0);
  x1 = std::min(x1, s.width() - 1), y1 = std::min(y1, s.height() - 1);
  PlacedEvidence e;
  e.map_width = s.width();
  e.resolution_m = s.resolution_m();
  if (x1 < x0 || y1 < y0) return e;
  e.window = {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
  e.log_odds.assign(static_cast<size_t>(e.window.num_cells()), 0.0f);
  // Static cell centre -> temporary grid coordinates is affine: start + x * step_x + y * step_y.
  const Eigen::Vector2d base = placed.WorldToGrid(s.CellCenter({x0, y0}));
  const Eigen::Vector2d step_x = placed.WorldToGrid(s.CellCenter({x0 + 1, y0})) - base;
  const Eigen::Vector2d step_y = placed.WorldToGrid(s.CellCenter({x0, y0 + 1})) - base;
  const std::vector<float>& cells = map.grid.cells();
  for (int y = 0; y < e.window.height; ++y) {
    for (int x = 0; x < e.window.width; ++x) {
      const Eigen::Vector2d g = base + x * step_x + y * step_y;
      const int tx = static_cast<int>(std::floor(g.x())), ty = static_cast<int>(std::floor(g.y()));
      if (tx < 0 || ty < 0 || tx >= placed.width() || ty >= placed.height()) continue;
      e.log_odds[static_cast<size_t>(y) * e.window.width + x] =
          cells[static_cast<size_t>(ty) * placed.width() + tx];
    }
  }
  return e;
}

}  // namespace fleetmap::aggregator
