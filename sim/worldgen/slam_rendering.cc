#include "sim/worldgen/slam_rendering.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmap::sim::worldgen {
namespace {

using core::CellState;

constexpr uint8_t kFreePx = 0, kExteriorPx = 128, kSolidPx = 255;
constexpr int kShift = 8;  // OpenCV's fixed-point drawing: 1/256 of a pixel

// Smooth noise in [0, 1): uniform values on a coarse lattice of `cell_px` pixels, bilinearly
// interpolated.
cv::Mat SmoothNoise(int rows, int cols, double cell_px, Rng& rng) {
  const int lr = std::max(2, static_cast<int>(rows / cell_px) + 2);
  const int lc = std::max(2, static_cast<int>(cols / cell_px) + 2);
  cv::Mat coarse(lr, lc, CV_32F);
  for (int r = 0; r < lr; ++r)
    for (int c = 0; c < lc; ++c) coarse.at<float>(r, c) = static_cast<float>(rng.Uniform(0, 1));
  cv::Mat fine;
  cv::resize(coarse, fine, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);
  return fine;
}

// A wall's centre line as SLAM draws it: every straight piece bent by a smooth bow (zero at
// its ends, so corners stay joined) and jittered about every metre.
Polyline BentWall(const Polyline& wall, const SlamLookOptions& o, Rng& rng) {
  Polyline out = {wall.front()};
  for (size_t i = 1; i < wall.size(); ++i) {
    const Eigen::Vector2d a = wall[i - 1], b = wall[i];
    const double len = (b - a).norm();
    if (len <= 0) continue;
    const Eigen::Vector2d dir = (b - a) / len, normal(-dir.y(), dir.x());
    const double bow = std::clamp(rng.Uniform(-1, 1) * o.wall_bend_per_m * len, -o.wall_bend_max_m,
                                  o.wall_bend_max_m);
    const int pieces = std::max(1, static_cast<int>(std::ceil(len)));
    for (int k = 1; k <= pieces; ++k) {
      const double s = static_cast<double>(k) / pieces;
      const double side =
          k == pieces ? 0.0
                      : bow * std::sin(M_PI * s) + rng.Uniform(-o.wall_jitter_m, o.wall_jitter_m);
      out.push_back(a + dir * (s * len) + normal * side);
    }
  }
  return out;
}

class Canvas {
 public:
  Canvas(int rows, int cols, const core::Pose2& building_in_map, double resolution_m)
      : image_(rows, cols, CV_8U, cv::Scalar(kFreePx)),
        to_map_(building_in_map),
        resolution_m_(resolution_m) {}

  // Building metres to fixed-point pixel coordinates (pixel centres at whole numbers).
  cv::Point Px(const Eigen::Vector2d& building) const {
    const Eigen::Vector2d p = to_map_.Apply(building) / resolution_m_ - Eigen::Vector2d(0.5, 0.5);
    return {static_cast<int>(std::lround(p.x() * (1 << kShift))),
            static_cast<int>(std::lround(p.y() * (1 << kShift)))};
  }
  void Polygon(const Polyline& building) {
    std::vector<cv::Point> pts;
    for (const auto& p : building) pts.push_back(Px(p));
    cv::fillPoly(image_, std::vector<std::vector<cv::Point>>{pts}, cv::Scalar(kSolidPx), cv::LINE_8,
                 kShift);
  }
  void ThickLine(const Polyline& building, double thickness_m) {
    const double h = thickness_m / 2;
    for (size_t i = 1; i < building.size(); ++i) {
      const Eigen::Vector2d a = building[i - 1], b = building[i];
      if ((b - a).norm() <= 0) continue;
      const Eigen::Vector2d d = (b - a).normalized(), n(-d.y(), d.x());
      Polygon({a + n * h, b + n * h, b - n * h, a - n * h});
    }
    // Round joints keep bent walls closed where two pieces meet at an angle.
    const int radius = static_cast<int>(std::lround(h / resolution_m_ * (1 << kShift)));
    for (const auto& p : building)
      cv::circle(image_, Px(p), radius, cv::Scalar(kSolidPx), cv::FILLED, cv::LINE_8, kShift);
  }
  cv::Mat& image() { return image_; }
  cv::Point Cell(const Eigen::Vector2d& building) const {
    const Eigen::Vector2d p = to_map_.Apply(building) / resolution_m_;
    return {static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y()))};
  }

 private:
  cv::Mat image_;
  core::Pose2 to_map_;
  double resolution_m_;
};

// Unseen stretches of wall: occupied cells about points along the wall become unknown.
void AddGaps(const FloorPlan& plan, const std::vector<Polyline>& bent, const Canvas& canvas,
             const SlamLookOptions& o, double res, Rng& rng, cv::Mat& state) {
  for (size_t w = 0; w < plan.walls.size(); ++w) {
    const double rate = plan.walls[w].outer ? o.gaps_per_m / 2 : o.gaps_per_m;
    const Polyline& line = bent[w];
    for (size_t i = 1; i < line.size(); ++i) {
      const double len = (line[i] - line[i - 1]).norm();
      if (!rng.Chance(rate * len)) continue;
      const Eigen::Vector2d at = line[i - 1] + (line[i] - line[i - 1]) * rng.Uniform(0, 1);
      const double radius_m = rng.Uniform(o.gap_min_m, o.gap_max_m) / 2;
      const int r = static_cast<int>(std::ceil((radius_m + plan.walls[w].thickness_m) / res));
      const cv::Point c = canvas.Cell(at);
      for (int y = std::max(0, c.y - r); y <= std::min(state.rows - 1, c.y + r); ++y)
        for (int x = std::max(0, c.x - r); x <= std::min(state.cols - 1, c.x + r); ++x)
          if (state.at<uint8_t>(y, x) == uint8_t(CellState::kOccupied) &&
              std::hypot(x - c.x, y - c.y) * res <= radius_m + plan.walls[w].thickness_m)
            state.at<uint8_t>(y, x) = uint8_t(CellState::kUnknown);
    }
  }
}

}  // namespace

core::Status SlamLookOptions::Validate() const {
  const bool ok = margin_m >= 0 && wall_bend_per_m >= 0 && wall_bend_max_m >= 0 &&
                  wall_jitter_m >= 0 && gaps_per_m >= 0 && gap_min_m >= 0 &&
                  gap_max_m >= gap_min_m && thicken_max_m >= 0 && ragged_fraction >= 0 &&
                  ragged_fraction <= 1 && speckle_per_m2 >= 0;
  if (!ok)
    return core::InvalidArgument(
        "SLAM look options must be >= 0, gap_max_m >= gap_min_m and ragged_fraction <= 1");
  return core::OkStatus();
}

core::Status RenderOptions::Validate() const {
  if (!(resolution_m >= 0.01 && resolution_m <= 0.5))
    return core::InvalidArgument("resolution_m must be within 0.01 and 0.5, not " +
                                 std::to_string(resolution_m));
  if (!std::isfinite(rotation_rad)) return core::InvalidArgument("rotation_rad must be finite");
  return look.Validate();
}

core::Result<RenderedMap> RenderFloorPlan(const FloorPlan& plan, const RenderOptions& o, Rng& rng) {
  FLEETMAP_RETURN_IF_ERROR(o.Validate());
  const double res = o.resolution_m;
  // The turned building's extent, walls included, decides the grid.
  const core::Pose2 turn(0, 0, o.rotation_rad);
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  const double slack = 0.5;  // walls drawn on the envelope reach out by half their thickness
  for (double x : {-slack, plan.length_m + slack})
    for (double y : {-slack, plan.width_m + slack}) {
      const Eigen::Vector2d p = turn.Apply({x, y});
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const Eigen::Vector2d offset = Eigen::Vector2d::Constant(o.look.margin_m) - lo;
  const core::Pose2 building_in_map(offset.x(), offset.y(), o.rotation_rad);
  const int cols = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * o.look.margin_m) / res));
  const int rows = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * o.look.margin_m) / res));
  const core::GridGeometry geometry(res, cols, rows);
  FLEETMAP_RETURN_IF_ERROR(geometry.Validate());

  Canvas canvas(rows, cols, building_in_map, res);
  std::vector<Polyline> bent;
  for (const Wall& w : plan.walls) {
    bent.push_back(BentWall(w.points_m, o.look, rng));
    // A wall thinner than a cell and a half would be drawn with holes where it runs between
    // cell centres; a laser sees it whole.
    canvas.ThickLine(bent.back(), std::max(w.thickness_m, 1.5 * res));
  }
  for (const Solid& s : plan.solids) canvas.Polygon(s.polygon_m);
  cv::Mat& label = canvas.image();
  // Outside: whatever the border reaches without crossing a wall.
  cv::floodFill(label, cv::Point(0, 0), cv::Scalar(kExteriorPx), nullptr, cv::Scalar(0),
                cv::Scalar(0), 4);

  // A laser sees surfaces: solid cells near free space are occupied, the rest unknown.
  cv::Mat not_free = label != kFreePx;
  cv::Mat to_free;
  cv::distanceTransform(not_free, to_free, cv::DIST_L2, 3);
  const cv::Mat thick = SmoothNoise(rows, cols, 0.5 / res, rng);
  const cv::Mat bumps = SmoothNoise(rows, cols, 0.15 / res, rng);
  cv::Mat state(rows, cols, CV_8U, cv::Scalar(uint8_t(CellState::kUnknown)));
  const float thicken_px = static_cast<float>(o.look.thicken_max_m / res);
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      const uint8_t l = label.at<uint8_t>(y, x);
      if (l == kFreePx) {
        state.at<uint8_t>(y, x) = uint8_t(CellState::kFree);
      } else if (l == kSolidPx &&
                 to_free.at<float>(y, x) <= 1.5f + thicken_px * thick.at<float>(y, x)) {
        state.at<uint8_t>(y, x) = uint8_t(CellState::kOccupied);
      }
    }
  }
  // Ragged faces: some free cells beside an obstacle drawn occupied.
  cv::Mat occupied = state == uint8_t(CellState::kOccupied);
  cv::Mat near_occupied;
  cv::dilate(occupied, near_occupied, cv::Mat::ones(3, 3, CV_8U));
  const float keep = static_cast<float>(1.0 - o.look.ragged_fraction);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x)
      if (state.at<uint8_t>(y, x) == uint8_t(CellState::kFree) && near_occupied.at<uint8_t>(y, x) &&
          bumps.at<float>(y, x) >= keep)
        state.at<uint8_t>(y, x) = uint8_t(CellState::kOccupied);
  AddGaps(plan, bent, canvas, o.look, res, rng, state);
  // Speckle: lone occupied cells in free space.
  const double free_m2 = cv::countNonZero(state == uint8_t(CellState::kFree)) * res * res;
  const int64_t speckles = std::llround(free_m2 * o.look.speckle_per_m2);
  for (int64_t i = 0; i < speckles; ++i) {
    const int x = rng.Int(0, cols - 1), y = rng.Int(0, rows - 1);
    if (state.at<uint8_t>(y, x) == uint8_t(CellState::kFree))
      state.at<uint8_t>(y, x) = uint8_t(CellState::kOccupied);
  }

  RenderedMap out{core::OccupancyGrid(geometry), building_in_map};
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x)
      out.grid.SetState({x, y}, static_cast<CellState>(state.at<uint8_t>(y, x)));
  return out;
}

}  // namespace fleetmap::sim::worldgen
