#include "vehicle_agent/localization/global_search.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmap::vehicle_agent {

core::Status GlobalSearchOptions::Validate() const {
  const bool ok = resolution_m > 0 && std::isfinite(resolution_m) && sigma_m > 0 &&
                  std::isfinite(sigma_m) && max_points >= 3 && max_point_range_m > 0 &&
                  angle_step_rad >= 0 && angle_step_rad < 1.0 && levels >= 1 && levels <= 12 &&
                  max_candidates >= 1 && min_score >= 0 && min_score <= 1 && distinct_m >= 0 &&
                  distinct_rad >= 0;
  if (!ok) {
    return core::InvalidArgument(
        "global search: resolution_m > 0, sigma_m > 0, max_points >= 3, max_point_range_m > 0, "
        "0 <= angle_step_rad < 1, levels 1..12, max_candidates >= 1, min_score in [0, 1], "
        "distinct_m and distinct_rad >= 0");
  }
  return core::OkStatus();
}

GlobalSearch::GlobalSearch(const core::OccupancyGrid& map, const GlobalSearchOptions& options)
    : options_(options), origin_(map.geometry().origin()) {
  BuildScoreGrid(map);
  BuildCoarserGrids();
}

void GlobalSearch::BuildScoreGrid(const core::OccupancyGrid& map) {
  const core::GridGeometry& g = map.geometry();
  const int k =
      std::max(1, static_cast<int>(std::lround(options_.resolution_m / g.resolution_m())));
  cell_m_ = k * g.resolution_m();
  width_ = (g.width() + k - 1) / k;
  height_ = (g.height() + k - 1) / k;
  // A search cell is an obstacle if any of its map cells is; the vehicle may stand on it if
  // none is and its middle map cell is known free.
  cv::Mat not_obstacle(height_, width_, CV_8U, cv::Scalar(255));
  free_.assign(static_cast<size_t>(width_) * height_, 0);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      if (map.state({x, y}) == core::CellState::kOccupied)
        not_obstacle.at<uint8_t>(y / k, x / k) = 0;
    }
  }
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const core::CellIndex middle{std::min(g.width() - 1, x * k + k / 2),
                                   std::min(g.height() - 1, y * k + k / 2)};
      free_[static_cast<size_t>(y) * width_ + x] =
          not_obstacle.at<uint8_t>(y, x) != 0 && map.state(middle) == core::CellState::kFree;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(not_obstacle, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  Grid base;
  base.width = width_;
  base.height = height_;
  base.value.resize(static_cast<size_t>(width_) * height_);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const double d = distance.at<float>(y, x) * cell_m_ / options_.sigma_m;
      base.value[static_cast<size_t>(y) * width_ + x] =
          static_cast<uint8_t>(std::lround(255.0 * std::exp(-0.5 * d * d)));
    }
  }
  grids_.push_back(std::move(base));
}

// Level h from level h - 1: a window of 2s cells from x is the windows of s cells from x and
// from x + s, on both axes.
void GlobalSearch::BuildCoarserGrids() {
  for (int h = 1; h < options_.levels; ++h) {
    const Grid& finer = grids_.back();
    const int s = 1 << (h - 1);
    Grid g;
    g.pad = (1 << h) - 1;
    g.width = width_ + g.pad;
    g.height = height_ + g.pad;
    g.value.resize(static_cast<size_t>(g.width) * g.height);
    for (int gy = 0; gy < g.height; ++gy) {
      for (int gx = 0; gx < g.width; ++gx) {
        const int x = gx - g.pad, y = gy - g.pad;
        g.value[static_cast<size_t>(gy) * g.width + gx] = static_cast<uint8_t>(std::max(
            {finer.At(x, y), finer.At(x + s, y), finer.At(x, y + s), finer.At(x + s, y + s)}));
      }
    }
    grids_.push_back(std::move(g));
  }
}

struct GlobalSearch::Node {
  int rotation = 0, x = 0, y = 0, level = 0;
  double bound = 0.0;
};

namespace {

// The end points used: at most max_points, spread over the scan, none beyond the range.
std::vector<Eigen::Vector2f> UsedPoints(const std::vector<Eigen::Vector2f>& all,
                                        const GlobalSearchOptions& o) {
  std::vector<Eigen::Vector2f> near;
  for (const Eigen::Vector2f& p : all)
    if (p.allFinite() && p.norm() <= o.max_point_range_m) near.push_back(p);
  if (static_cast<int>(near.size()) <= o.max_points) return near;
  std::vector<Eigen::Vector2f> used;
  const double stride = static_cast<double>(near.size()) / o.max_points;
  for (int i = 0; i < o.max_points; ++i) used.push_back(near[static_cast<size_t>(i * stride)]);
  return used;
}

}  // namespace

double GlobalSearch::Score(const std::vector<Eigen::Vector2f>& points_in_base,
                           const core::Pose2& base_in_map) const {
  const std::vector<Eigen::Vector2f> points = UsedPoints(points_in_base, options_);
  if (points.size() < 3) return 0.0;
  const core::Pose2 base_in_grid = origin_.Inverse() * base_in_map;
  const double c = std::cos(base_in_grid.theta_rad), s = std::sin(base_in_grid.theta_rad);
  int sum = 0;
  for (const Eigen::Vector2f& p : points) {
    const double gx = base_in_grid.x_m + c * p.x() - s * p.y();
    const double gy = base_in_grid.y_m + s * p.x() + c * p.y();
    // Search's vehicle cell is floor(x / cell) and its offsets are rounded: the same here.
    sum += grids_.front().At(static_cast<int>(std::floor(gx / cell_m_)),
                             static_cast<int>(std::floor(gy / cell_m_)));
  }
  return sum / (255.0 * points.size());
}

std::vector<GlobalCandidate> GlobalSearch::Search(
    const std::vector<Eigen::Vector2f>& points_in_base) const {
  const std::vector<Eigen::Vector2f> points = UsedPoints(points_in_base, options_);
  if (points.size() < 3) return {};
  double reach_m = cell_m_;
  for (const Eigen::Vector2f& p : points) reach_m = std::max(reach_m, double(p.norm()));
  double step = options_.angle_step_rad;
  if (step == 0.0) {
    const double r = cell_m_ / reach_m;
    step = std::clamp(std::acos(1.0 - 0.5 * r * r), 0.002, 0.1);
  }
  const int rotations = static_cast<int>(std::ceil(2 * M_PI / step));
  step = 2 * M_PI / rotations;

  // Per heading, each point's offset from the vehicle's cell, in cells.
  std::vector<std::vector<Eigen::Vector2i>> offsets(static_cast<size_t>(rotations));
  for (int r = 0; r < rotations; ++r) {
    const double c = std::cos(r * step), s = std::sin(r * step);
    for (const Eigen::Vector2f& p : points) {
      const double gx = c * p.x() - s * p.y(), gy = s * p.x() + c * p.y();
      offsets[static_cast<size_t>(r)].emplace_back(
          static_cast<int>(std::floor(0.5 + gx / cell_m_)),
          static_cast<int>(std::floor(0.5 + gy / cell_m_)));
    }
  }
  const double scale = 1.0 / (255.0 * points.size());
  const auto bound = [&](const Node& n) {
    const Grid& grid = grids_[static_cast<size_t>(n.level)];
    int sum = 0;
    for (const Eigen::Vector2i& o : offsets[static_cast<size_t>(n.rotation)])
      sum += grid.At(n.x + o.x(), n.y + o.y());
    return sum * scale;
  };

  std::vector<GlobalCandidate> best;  // distinct, at most max_candidates
  const auto threshold = [&] {
    if (static_cast<int>(best.size()) < options_.max_candidates) return options_.min_score;
    double worst = 1.0;
    for (const GlobalCandidate& c : best) worst = std::min(worst, c.score);
    return worst;
  };
  const auto offer = [&](const GlobalCandidate& c) {
    for (GlobalCandidate& b : best) {
      const core::Pose2 d = core::Between(b.base_in_map, c.base_in_map);
      if (std::hypot(d.x_m, d.y_m) < options_.distinct_m &&
          std::abs(d.theta_rad) < options_.distinct_rad) {
        if (c.score > b.score) b = c;
        return;
      }
    }
    if (static_cast<int>(best.size()) < options_.max_candidates) {
      best.push_back(c);
      return;
    }
    auto worst = std::min_element(best.begin(), best.end(),
                                  [](const auto& a, const auto& b) { return a.score < b.score; });
    if (c.score > worst->score) *worst = c;
  };

  const int top = levels() - 1;
  std::vector<Node> stack;
  {
    std::vector<Node> first;
    const int s = 1 << top;
    for (int r = 0; r < rotations; ++r) {
      for (int y = 0; y < height_; y += s) {
        for (int x = 0; x < width_; x += s) {
          Node n{r, x, y, top, 0.0};
          n.bound = bound(n);
          if (n.bound >= options_.min_score) first.push_back(n);
        }
      }
    }
    // The stack pops the best first.
    std::sort(first.begin(), first.end(),
              [](const Node& a, const Node& b) { return a.bound < b.bound; });
    stack = std::move(first);
  }
  while (!stack.empty()) {
    const Node n = stack.back();
    stack.pop_back();
    if (n.bound < threshold() || (n.bound == threshold() && !best.empty() &&
                                  static_cast<int>(best.size()) == options_.max_candidates))
      continue;
    if (n.level == 0) {
      if (!free_[static_cast<size_t>(n.y) * width_ + n.x]) continue;
      const core::Pose2 in_grid((n.x + 0.5) * cell_m_, (n.y + 0.5) * cell_m_,
                                core::NormalizeAngle(n.rotation * step));
      offer({origin_ * in_grid, n.bound});
      continue;
    }
    const int s = 1 << (n.level - 1);
    std::vector<Node> children;
    for (int dy : {0, s}) {
      for (int dx : {0, s}) {
        Node c{n.rotation, n.x + dx, n.y + dy, n.level - 1, 0.0};
        if (c.x >= width_ || c.y >= height_) continue;
        c.bound = bound(c);
        children.push_back(c);
      }
    }
    std::sort(children.begin(), children.end(),
              [](const Node& a, const Node& b) { return a.bound < b.bound; });
    stack.insert(stack.end(), children.begin(), children.end());
  }
  std::sort(best.begin(), best.end(),
            [](const GlobalCandidate& a, const GlobalCandidate& b) { return a.score > b.score; });
  return best;
}

}  // namespace fleetmap::vehicle_agent
