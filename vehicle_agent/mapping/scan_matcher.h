// Gauss-Newton scan-to-map matching (hector_slam): finds the pose that puts the scan's end
// points on occupied cells of the interpolated map, coarse level to fine. Unlike hector, the
// odometry prediction enters as a prior term, so that a featureless aisle, where the scan
// constrains nothing along it, keeps the odometry's estimate instead of sliding.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"
#include "vehicle_agent/mapping/multires_map.h"

namespace fleetmap::vehicle_agent {

struct ScanMatcherOptions {
  int coarse_iterations = 3;  // Gauss-Newton steps on each coarser level
  int fine_iterations = 5;    // ... and on the finest level
  // The odometry prior: the standard deviation of one scan's odometry error is
  // base + fraction * motion since the previous scan. 0 for the base switches the prior off.
  double prior_sigma_xy_m = 0.005;          // base, metres
  double prior_sigma_xy_per_m = 0.05;       // per metre travelled
  double prior_sigma_theta_rad = 0.005;     // base, radians
  double prior_sigma_theta_per_rad = 0.05;  // per radian turned
  // Noise of one end point's map value (probability units); weighs scan against prior.
  double sigma_map = 0.25;
  // Before Gauss-Newton, the heading is searched on the coarsest level within +-(base +
  // fraction * |odometry rotation since the previous scan|): odometry that lags a fast turn
  // (aces' ODOM lines come at the scan rate, so a scan's odometry is up to one period old)
  // can leave the descent in a rotated minimum, and each such slip bends the map. 0 and 0
  // switch the search off. Measured on the SLAM benchmark logs (docs/localization.md).
  double heading_search_base_rad = 0.035;  // 2 degrees
  double heading_search_per_rad = 1.0;
  double max_step_rad = 0.2;  // largest rotation of one iteration, for stability
  // A match farther than this from the prediction is taken for a false minimum (a vehicle
  // cannot slip that far between two scans): the prediction is kept instead.
  double max_correction_m = 0.3;
  double max_correction_rad = 0.2;
  core::Status Validate() const;
};

struct MatchResult {
  core::Pose2 pose;                                       // matched base pose in the map's frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  // of the finest level, with prior
  int points = 0;
  bool rejected = false;  // the match strayed too far: `pose` is the prediction
};

// `points_in_base` are the scan's end points in the vehicle base frame (metres);
// `prediction` is the previous pose moved by `odometry_delta`, which also sets the prior's
// width.
MatchResult MatchScan(const MultiResolutionMap& map,
                      const std::vector<Eigen::Vector2d>& points_in_base,
                      const core::Pose2& prediction, const core::Pose2& odometry_delta,
                      const ScanMatcherOptions& options);

// Mean occupancy probability of the finest level at the points placed by `pose`: how well a
// match fits (1: every point on a certain wall). Diagnostics only, so MatchScan does not pay
// for it.
double MeanMapValue(const MultiResolutionMap& map,
                    const std::vector<Eigen::Vector2d>& points_in_base, const core::Pose2& pose);

}  // namespace fleetmap::vehicle_agent
