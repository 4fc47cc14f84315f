#include "core/map/ray_caster.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmap::core {

RayCaster::RayCaster(const GridGeometry& geometry)
    : geometry_(geometry),
      solid_(static_cast<size_t>(geometry.num_cells()), 0),
      clearance_cells_(static_cast<size_t>(geometry.num_cells()), 1e9f) {}

void RayCaster::SetSolid(std::vector<uint8_t> solid) {
  assert(static_cast<int64_t>(solid.size()) == geometry_.num_cells());
  solid_ = std::move(solid);
  // distanceTransform measures the distance to the nearest zero pixel: zero = solid.
  cv::Mat free_mask(geometry_.height(), geometry_.width(), CV_8UC1);
  for (size_t i = 0; i < solid_.size(); ++i) free_mask.data[i] = solid_[i] ? 0 : 255;
  cv::Mat distance(geometry_.height(), geometry_.width(), CV_32FC1, clearance_cells_.data());
  cv::distanceTransform(free_mask, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
}

RayHit RayCaster::Cast(const Eigen::Vector2d& origin, double angle_rad, double max_range_m) const {
  // Work in cell units of the grid frame.
  const double res = geometry_.resolution_m();
  const Eigen::Vector2d o = geometry_.WorldToGrid(origin);
  const double dir_angle = angle_rad - geometry_.origin().theta_rad;
  const double dx = std::cos(dir_angle), dy = std::sin(dir_angle);
  const double t_max = max_range_m / res;
  const int w = geometry_.width(), h = geometry_.height();
  double t = 0.0;
  while (t < t_max) {
    const double px = o.x() + dx * t, py = o.y() + dy * t;
    const int cx = static_cast<int>(std::floor(px)), cy = static_cast<int>(std::floor(py));
    if (cx < 0 || cy < 0 || cx >= w || cy >= h) return {};
    const size_t idx = static_cast<size_t>(cy) * w + cx;
    if (solid_[idx]) return {t * res, {cx, cy}};
    // A point in this cell is at least clearance - sqrt(2) cells from any solid cell.
    const double safe_step = clearance_cells_[idx] - 1.5;
    if (safe_step >= 1.0) {
      t += safe_step;
      continue;
    }
    // Step to where the ray leaves this cell.
    const double tx = dx > 0 ? (cx + 1 - px) / dx : dx < 0 ? (cx - px) / dx : kNoHit;
    const double ty = dy > 0 ? (cy + 1 - py) / dy : dy < 0 ? (cy - py) / dy : kNoHit;
    t += std::min(tx, ty) + 1e-9;
  }
  return {};
}

}  // namespace fleetmap::core
