#include "vehicle_agent/mapping/scan_matcher.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "vehicle_agent/mapping/map_interpolator.h"

namespace fleetmap::vehicle_agent {
namespace {

struct NormalEquations {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
};

// Accumulates J^T J and J^T r of residuals r_i = 1 - M(S_i(pose)).
// Every `stride`-th point only: points closer together than a level's cells add nothing there.
NormalEquations Accumulate(const MapInterpolator& map, const std::vector<Eigen::Vector2d>& points,
                           size_t stride, const core::Pose2& pose, double weight) {
  NormalEquations ne;
  const double c = std::cos(pose.theta_rad), s = std::sin(pose.theta_rad);
  for (size_t i = 0; i < points.size(); i += stride) {
    const Eigen::Vector2d& p = points[i];
    const Eigen::Vector2d world(pose.x_m + c * p.x() - s * p.y(), pose.y_m + s * p.x() + c * p.y());
    const InterpolatedValue m = map.At(world);
    const double d_theta = m.gradient_per_m.x() * (-s * p.x() - c * p.y()) +
                           m.gradient_per_m.y() * (c * p.x() - s * p.y());
    const Eigen::Vector3d j(m.gradient_per_m.x(), m.gradient_per_m.y(), d_theta);
    ne.h += weight * j * j.transpose();
    ne.b += weight * j * (1.0 - m.value);
  }
  return ne;
}

// Sum of the map values at the points placed by `pose`: the correlation a coarse search ranks.
double Score(const MapInterpolator& map, const std::vector<Eigen::Vector2d>& points, size_t stride,
             const core::Pose2& pose) {
  const double c = std::cos(pose.theta_rad), s = std::sin(pose.theta_rad);
  double sum = 0.0;
  for (size_t i = 0; i < points.size(); i += stride) {
    const Eigen::Vector2d& p = points[i];
    sum += map.Value({pose.x_m + c * p.x() - s * p.y(), pose.y_m + s * p.x() + c * p.y()});
  }
  return sum;
}

// Gauss-Newton's basin on the coarsest level is a cell or two wide: a heading off by a few
// degrees (stale odometry in a fast turn) moves far end points farther than that, and the
// descent can settle in a wrong, rotated minimum. So the heading is first searched on the
// coarsest level over the odometry's rotational uncertainty, in steps that move the farthest
// point by half a coarse cell; the prediction wins ties.
core::Pose2 SearchHeading(const MultiResolutionMap& map, const std::vector<Eigen::Vector2d>& points,
                          const core::Pose2& prediction, double window_rad) {
  const core::OccupancyGrid& coarsest = map.level(map.levels() - 1);
  double reach_m = 0.0;
  for (const Eigen::Vector2d& p : points) reach_m = std::max(reach_m, p.norm());
  if (window_rad <= 0 || reach_m <= 0) return prediction;
  const double step_rad = 0.5 * coarsest.geometry().resolution_m() / reach_m;
  const int steps = std::min(64, static_cast<int>(std::ceil(window_rad / step_rad)));
  const MapInterpolator interpolator(&coarsest);
  const size_t stride = size_t{1} << (map.levels() - 1);
  core::Pose2 best = prediction;
  double best_score = Score(interpolator, points, stride, prediction);
  for (int i = -steps; i <= steps; ++i) {
    if (i == 0) continue;
    const core::Pose2 candidate(
        prediction.x_m, prediction.y_m,
        core::NormalizeAngle(prediction.theta_rad + i * window_rad / steps));
    const double score = Score(interpolator, points, stride, candidate);
    if (score > best_score * (1.0 + 1e-3)) best = candidate, best_score = score;
  }
  return best;
}

Eigen::Matrix3d PriorInformation(const ScanMatcherOptions& o, const core::Pose2& motion) {
  if (o.prior_sigma_xy_m <= 0 || o.prior_sigma_theta_rad <= 0) return Eigen::Matrix3d::Zero();
  const double xy =
      o.prior_sigma_xy_m + o.prior_sigma_xy_per_m * std::hypot(motion.x_m, motion.y_m);
  const double th =
      o.prior_sigma_theta_rad + o.prior_sigma_theta_per_rad * std::abs(motion.theta_rad);
  return Eigen::Vector3d(1 / (xy * xy), 1 / (xy * xy), 1 / (th * th)).asDiagonal();
}

}  // namespace

core::Status ScanMatcherOptions::Validate() const {
  if (!(coarse_iterations >= 0 && fine_iterations >= 1 && prior_sigma_xy_m >= 0 &&
        prior_sigma_theta_rad >= 0 && prior_sigma_xy_per_m >= 0 && prior_sigma_theta_per_rad >= 0 &&
        sigma_map > 0 && heading_search_base_rad >= 0 && heading_search_per_rad >= 0 &&
        max_step_rad > 0 && max_correction_m > 0 && max_correction_rad > 0)) {
    return core::InvalidArgument("scan matcher options out of range");
  }
  return core::OkStatus();
}

MatchResult MatchScan(const MultiResolutionMap& map, const std::vector<Eigen::Vector2d>& points,
                      const core::Pose2& prediction, const core::Pose2& odometry_delta,
                      const ScanMatcherOptions& options) {
  MatchResult result;
  result.pose = prediction;
  result.points = static_cast<int>(points.size());
  if (points.empty()) return result;
  const Eigen::Matrix3d prior = PriorInformation(options, odometry_delta);
  const double weight = 1.0 / (options.sigma_map * options.sigma_map);
  const double search_rad = options.heading_search_base_rad +
                            options.heading_search_per_rad * std::abs(odometry_delta.theta_rad);
  result.pose = SearchHeading(map, points, prediction, search_rad);
  for (int level = map.levels() - 1; level >= 0; --level) {
    const MapInterpolator interpolator(&map.level(level));
    const int iterations = level == 0 ? options.fine_iterations : options.coarse_iterations;
    for (int it = 0; it < iterations; ++it) {
      NormalEquations ne =
          Accumulate(interpolator, points, size_t{1} << level, result.pose, weight * (1 << level));
      const core::Pose2 off =
          core::Pose2(prediction.x_m - result.pose.x_m, prediction.y_m - result.pose.y_m,
                      core::NormalizeAngle(prediction.theta_rad - result.pose.theta_rad));
      ne.h += prior;
      ne.b += prior * Eigen::Vector3d(off.x_m, off.y_m, off.theta_rad);
      if (std::abs(ne.h.determinant()) < 1e-12) break;  // nothing to match against
      Eigen::Vector3d step = ne.h.ldlt().solve(ne.b);
      if (!step.allFinite()) break;
      step.z() = std::clamp(step.z(), -options.max_step_rad, options.max_step_rad);
      result.pose = core::Pose2(result.pose.x_m + step.x(), result.pose.y_m + step.y(),
                                core::NormalizeAngle(result.pose.theta_rad + step.z()));
      if (level == 0) result.information = ne.h;
      if (step.head<2>().norm() < 1e-4 && std::abs(step.z()) < 1e-4) break;  // 0.1 mm
    }
  }
  const core::Pose2 correction = core::Between(prediction, result.pose);
  if (std::hypot(correction.x_m, correction.y_m) > options.max_correction_m ||
      std::abs(correction.theta_rad) > options.max_correction_rad) {
    result.pose = prediction;
    result.rejected = true;
  }
  return result;
}

double MeanMapValue(const MultiResolutionMap& map, const std::vector<Eigen::Vector2d>& points,
                    const core::Pose2& pose) {
  if (points.empty()) return 0.0;
  return Score(MapInterpolator(&map.finest()), points, 1, pose) / points.size();
}

}  // namespace fleetmap::vehicle_agent
