#include "core/map/grid_geometry.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fleetmap::core {

GridGeometry::GridGeometry(double resolution_m, int width_cells, int height_cells, Pose2 origin)
    : resolution_m_(resolution_m), width_(width_cells), height_(height_cells), origin_(origin) {}

Status GridGeometry::Validate() const {
  if (!std::isfinite(resolution_m_) || resolution_m_ <= 0.0) {
    return InvalidArgument("resolution must be a positive number of metres, got " +
                           std::to_string(resolution_m_));
  }
  if (width_ <= 0 || height_ <= 0) {
    return InvalidArgument("grid size must be positive, got " + std::to_string(width_) + " x " +
                           std::to_string(height_));
  }
  if (num_cells() > kMaxGridCells) {
    return OutOfRange("grid of " + std::to_string(width_) + " x " + std::to_string(height_) +
                      " cells exceeds the limit of " + std::to_string(kMaxGridCells) + " cells");
  }
  if (!origin_.IsFinite()) return InvalidArgument("grid origin is not finite");
  return OkStatus();
}

bool GridGeometry::Contains(const CellWindow& w) const {
  return w.width >= 0 && w.height >= 0 && w.x0 >= 0 && w.y0 >= 0 &&
         int64_t{w.x0} + w.width <= width_ && int64_t{w.y0} + w.height <= height_;
}

CellWindow GridGeometry::Grown(const CellWindow& w, int cells) const {
  if (w.width <= 0 || w.height <= 0) return {};
  const int x0 = std::max(0, w.x0 - cells), y0 = std::max(0, w.y0 - cells);
  const int x1 = std::min(width_, w.x0 + w.width + cells);
  const int y1 = std::min(height_, w.y0 + w.height + cells);
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

CellWindow Union(const CellWindow& a, const CellWindow& b) {
  if (a.width <= 0 || a.height <= 0) return b;
  if (b.width <= 0 || b.height <= 0) return a;
  const int x0 = std::min(a.x0, b.x0), y0 = std::min(a.y0, b.y0);
  const int x1 = std::max(a.x0 + a.width, b.x0 + b.width);
  const int y1 = std::max(a.y0 + a.height, b.y0 + b.height);
  return {x0, y0, x1 - x0, y1 - y0};
}

Eigen::Vector2d GridGeometry::WorldToGrid(const Eigen::Vector2d& world) const {
  return origin_.Inverse().Apply(world) / resolution_m_;
}

CellIndex GridGeometry::WorldToCell(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d g = WorldToGrid(world);
  return {static_cast<int>(std::floor(g.x())), static_cast<int>(std::floor(g.y()))};
}

Eigen::Vector2d GridGeometry::CellCenter(const CellIndex& c) const {
  return origin_.Apply(Eigen::Vector2d(c.x + 0.5, c.y + 0.5) * resolution_m_);
}

bool GridGeometry::operator==(const GridGeometry& o) const {
  return resolution_m_ == o.resolution_m_ && width_ == o.width_ && height_ == o.height_ &&
         origin_.x_m == o.origin_.x_m && origin_.y_m == o.origin_.y_m &&
         origin_.theta_rad == o.origin_.theta_rad;
}

std::string GridGeometry::ToString() const {
  std::ostringstream s;
  s << width_ << " x " << height_ << " cells at " << resolution_m_ << " m, origin "
    << origin_.ToString();
  return s.str();
}

}  // namespace fleetmap::core
