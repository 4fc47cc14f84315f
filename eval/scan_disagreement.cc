#include "eval/scan_disagreement.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::eval {

void ScanDisagreement::SetMap(const core::OccupancyGrid& map,
                              const std::vector<uint8_t>& semi_static) {
  geometry_ = map.geometry();
  const int w = geometry_.width(), h = geometry_.height(), r = options_.clearance_cells;
  const core::TriStateClassifier classify;
  // Occupied cells dilated by r (a square), then free cells outside them.
  std::vector<uint8_t> near(map.cells().size(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (classify(map.cells()[size_t(y) * w + x]) != core::CellState::kOccupied) continue;
      for (int dy = std::max(0, y - r); dy <= std::min(h - 1, y + r); ++dy)
        for (int dx = std::max(0, x - r); dx <= std::min(w - 1, x + r); ++dx)
          near[size_t(dy) * w + dx] = 1;
    }
  }
  free_far_.assign(near.size(), 0);
  for (size_t i = 0; i < near.size(); ++i)
    free_far_[i] = !near[i] && classify(map.cells()[i]) == core::CellState::kFree;
  semi_static_ = semi_static;
  any_semi_static_ =
      std::any_of(semi_static.begin(), semi_static.end(), [](uint8_t s) { return s; });
}

bool ScanDisagreement::PassesObstacle(const Eigen::Vector2d& from, const Eigen::Vector2d& direction,
                                      double length_m) const {
  // Walk in grid coordinates, one cell per step.
  const Eigen::Vector2d g0 = geometry_.WorldToGrid(from);
  const Eigen::Vector2d dg =
      geometry_.WorldToGrid(from + direction * geometry_.resolution_m()) - g0;
  const int steps = static_cast<int>(length_m / geometry_.resolution_m());
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector2d g = g0 + k * dg;
    const int x = static_cast<int>(std::floor(g.x())), y = static_cast<int>(std::floor(g.y()));
    if (x < 0 || y < 0 || x >= geometry_.width() || y >= geometry_.height()) return false;
    if (semi_static_[size_t(y) * geometry_.width() + x]) return true;
  }
  return false;
}

Disagreement ScanDisagreement::Judge(const core::LaserScan& scan,
                                     const core::Pose2& scanner_in_map) const {
  Disagreement d;
  const double res = geometry_.resolution_m();
  std::vector<uint8_t> marked(scan.size(), 0);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < scan.size(); ++i) {
    const double a = scanner_in_map.theta_rad + scan.angle(i);
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    const bool valid = scan.IsValidReturn(i);
    const double range = valid ? scan.ranges_m[i] : options_.max_range_m;
    const Eigen::Vector2d end = scanner_in_map.translation() + range * dir;
    if (valid && range <= options_.max_range_m) {
      const core::CellIndex c = geometry_.WorldToCell(end);
      marked[i] = marked[i] || (geometry_.Contains(c) && free_far_[size_t(geometry_.Index(c))]);
    }
    if (!marked[i] && any_semi_static_ && i % size_t(options_.pass_beam_step) == 0) {
      const double length =
          std::min(range, options_.max_range_m) - options_.pass_end_margin_cells * res;
      marked[i] = PassesObstacle(scanner_in_map.translation(), dir, length);
      for (size_t k = i + 1; marked[i] && k < std::min(scan.size(), i + options_.pass_beam_step);
           ++k)
        marked[k] = 1;
    }
    if (marked[i]) sum += end;
  }
  int run = 0;
  for (size_t i = 0; i < scan.size(); ++i) {
    run = marked[i] ? run + 1 : 0;
    d.longest_run = std::max(d.longest_run, run);
    d.disagreeing_beams += marked[i];
  }
  if (d.disagreeing_beams > 0) d.centroid = sum / d.disagreeing_beams;
  return d;
}

}  // namespace fleetmap::eval
