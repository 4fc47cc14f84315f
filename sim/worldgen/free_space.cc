#include "sim/worldgen/free_space.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <queue>

namespace fleetmap::sim::worldgen {

core::Result<FreeSpace> FreeSpace::Of(const core::OccupancyGrid& map, double clearance_m) {
  const core::GridGeometry& g = map.geometry();
  cv::Mat free(g.height(), g.width(), CV_8U);
  const core::TriStateClassifier classify;
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x)
      free.at<uint8_t>(y, x) =
          classify(map.cells()[g.Index({x, y})]) == core::CellState::kFree ? 255 : 0;
  cv::Mat radius;  // cells to the nearest cell that is not free
  cv::distanceTransform(free, radius, cv::DIST_L2, 3);
  FreeSpace s;
  s.clearance_m_ = clearance_m;
  const int k = std::max(1, static_cast<int>(std::lround(0.1 / g.resolution_m())));
  s.cell_m_ = k * g.resolution_m();
  s.width_ = g.width() / k;
  s.height_ = g.height() / k;
  s.grid_ = core::GridGeometry(s.cell_m_, s.width_, s.height_, g.origin());
  if (s.width_ < 2 || s.height_ < 2) return core::FailedPrecondition("the map is too small");
  cv::Mat inside(s.height_, s.width_, CV_8U, cv::Scalar(0));
  s.free_radius_m_.assign(static_cast<size_t>(s.width_) * s.height_, 0.0f);
  for (int y = 0; y < s.height_; ++y) {
    for (int x = 0; x < s.width_; ++x) {
      float least = 1e9f;
      for (int dy = 0; dy < k; ++dy)
        for (int dx = 0; dx < k; ++dx)
          least = std::min(least, radius.at<float>(y * k + dy, x * k + dx));
      const float metres = static_cast<float>(least * g.resolution_m());
      s.free_radius_m_[static_cast<size_t>(y) * s.width_ + x] = metres;
      if (metres >= clearance_m) inside.at<uint8_t>(y, x) = 1;
    }
  }
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(inside, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  for (int l = 1; l < n; ++l)
    if (best == 0 || stats.at<int>(l, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA))
      best = l;
  if (best == 0)
    return core::FailedPrecondition("no free space " + std::to_string(clearance_m) +
                                    " m from every wall, object and unknown cell");
  s.inside_.assign(s.free_radius_m_.size(), 0);
  for (int y = 0; y < s.height_; ++y)
    for (int x = 0; x < s.width_; ++x)
      if (labels.at<int>(y, x) == best) {
        s.inside_[static_cast<size_t>(y) * s.width_ + x] = 1;
        s.piece_.push_back(y * s.width_ + x);
      }
  return s;
}

double FreeSpace::area_m2() const { return piece_.size() * cell_m_ * cell_m_; }

int FreeSpace::Cell(const Eigen::Vector2d& p) const {
  const core::CellIndex c = grid_.WorldToCell(p);
  return grid_.Contains(c) ? static_cast<int>(grid_.Index(c)) : -1;
}

Eigen::Vector2d FreeSpace::Centre(int cell) const {
  return grid_.CellCenter({cell % width_, cell / width_});
}

bool FreeSpace::Contains(const Eigen::Vector2d& p) const {
  const int c = Cell(p);
  return c >= 0 && inside_[c];
}

bool FreeSpace::SegmentInside(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const int steps = static_cast<int>((b - a).norm() / (cell_m_ / 2)) + 1;
  for (int i = 0; i <= steps; ++i)
    if (!Contains(a + (b - a) * (static_cast<double>(i) / steps))) return false;
  return true;
}

double FreeSpace::FreeRadiusAt(const Eigen::Vector2d& p) const {
  const int c = Cell(p);
  return c < 0 ? 0.0 : free_radius_m_[c];
}

Eigen::Vector2d FreeSpace::RandomPoint(Rng& rng) const {
  return Centre(piece_[rng.Int(0, static_cast<int>(piece_.size()) - 1)]);
}

std::vector<Eigen::Vector2d> FreeSpace::Path(const Eigen::Vector2d& from,
                                             const Eigen::Vector2d& to) const {
  const int start = Cell(from), goal = Cell(to);
  if (start < 0 || goal < 0 || !inside_[start] || !inside_[goal]) return {};
  std::vector<float> cost(inside_.size(), 1e30f);
  std::vector<int> parent(inside_.size(), -1);
  using Item = std::pair<float, int>;  // (cost + heuristic, cell)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  const Eigen::Vector2d goal_centre = Centre(goal);
  auto heuristic = [&](int c) { return static_cast<float>((Centre(c) - goal_centre).norm()); };
  cost[start] = 0;
  open.push({heuristic(start), start});
  while (!open.empty()) {
    const auto [f, c] = open.top();
    open.pop();
    if (c == goal) break;
    if (f - heuristic(c) > cost[c] + 1e-4f) continue;  // a stale entry
    const int cx = c % width_, cy = c / width_;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = cx + dx, ny = cy + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
        const int n = ny * width_ + nx;
        if (!inside_[n]) continue;
        // Length, plus up to as much again close to the clearance limit: aisle middles win.
        const float step = static_cast<float>(std::hypot(dx, dy) * cell_m_);
        const float near = static_cast<float>(clearance_m_ / std::max(1e-3f, free_radius_m_[n]));
        const float next = cost[c] + step * (1.0f + near);
        if (next < cost[n]) {
          cost[n] = next;
          parent[n] = c;
          open.push({next + heuristic(n), n});
        }
      }
    }
  }
  if (parent[goal] < 0 && goal != start) return {};
  std::vector<Eigen::Vector2d> cells;
  for (int c = goal; c >= 0; c = parent[c]) cells.push_back(Centre(c));
  std::reverse(cells.begin(), cells.end());
  cells.front() = from;
  cells.back() = to;
  // String pulling: from each waypoint, straight on along the path while it stays in sight.
  std::vector<Eigen::Vector2d> legs = {cells.front()};
  size_t i = 0;
  while (i + 1 < cells.size()) {
    size_t j = i + 1;
    while (j + 1 < cells.size() && SegmentInside(cells[i], cells[j + 1])) ++j;
    legs.push_back(cells[j]);
    i = j;
  }
  return legs;
}

}  // namespace fleetmap::sim::worldgen
