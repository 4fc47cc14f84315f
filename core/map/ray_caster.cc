#include "core/map/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace fleetmap::core {

RayCaster::RayCaster(const GridGeometry& geometry, double max_clearance_m)
    : geometry_(geometry),
      max_clearance_cells_(max_clearance_m > 0
                               ? static_cast<float>(max_clearance_m / geometry.resolution_m())
                               : std::numeric_limits<float>::infinity()),
      reach_cells_(max_clearance_m > 0 ? static_cast<int>(std::ceil(max_clearance_cells_)) + 1
                                       : std::max(geometry.width(), geometry.height())),
      solid_(static_cast<size_t>(geometry.num_cells()), 0),
      clearance_cells_(static_cast<size_t>(geometry.num_cells()), 1e9f) {}

void RayCaster::SetSolid(std::vector<uint8_t> solid) {
  assert(static_cast<int64_t>(solid.size()) == geometry_.num_cells());
  solid_ = std::move(solid);
  Recompute(geometry_.full_window());
}

void RayCaster::UpdateSolid(const CellWindow& changed,
                            const std::vector<uint8_t>& solid_in_window) {
  assert(geometry_.Contains(changed));
  assert(static_cast<int64_t>(solid_in_window.size()) == changed.num_cells());
  for (int y = 0; y < changed.height; ++y)
    std::copy_n(solid_in_window.begin() + size_t(y) * changed.width, changed.width,
                solid_.begin() + size_t(y + changed.y0) * geometry_.width() + changed.x0);
  // A cell further than the cap from every change had its nearest solid cells within the cap
  // unchanged: its capped clearance stays.
  const CellWindow out = geometry_.Grown(changed, reach_cells_);
  if (out.num_cells() > 0) Recompute(out);
}

void RayCaster::Recompute(const CellWindow& out) {
  // A cell's nearest solid cell, when nearer than the cap, lies within the reach of it.
  const CellWindow source = geometry_.Grown(out, reach_cells_);
  // distanceTransform measures the distance to the nearest zero pixel: zero = solid.
  cv::Mat free_mask(source.height, source.width, CV_8UC1);
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x)
      free_mask.at<uint8_t>(y, x) =
          solid_[size_t(y + source.y0) * geometry_.width() + (x + source.x0)] ? 0 : 255;
  cv::Mat distance(source.height, source.width, CV_32FC1);
  cv::distanceTransform(free_mask, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  for (int y = out.y0; y < out.y0 + out.height; ++y)
    for (int x = out.x0; x < out.x0 + out.width; ++x)
      clearance_cells_[size_t(y) * geometry_.width() + x] =
          std::min(distance.at<float>(y - source.y0, x - source.x0), max_clearance_cells_);
}

RayHit RayCaster::Cast(const Eigen::Vector2d& origin, double angle_rad, double max_range_m) const {
  // Work in cell units of the grid frame.
  const double res = geometry_.resolution_m();
  const Eigen::Vector2d o = geometry_.WorldToGrid(origin);
  const double dir_angle = angle_rad - geometry_.origin().theta_rad;
  // A component this small moves the ray less than a millionth of a cell over any range; kept,
  // a ray started on a cell boundary (cos of 90 deg is 6e-17, not 0) would stay on it in
  // floating point and step 1e-9 at a time.
  const auto component = [](double c) { return std::abs(c) < 1e-9 ? 0.0 : c; };
  const double dx = component(std::cos(dir_angle)), dy = component(std::sin(dir_angle));
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
