// The vehicle's own localization as the localizer uses it (LocalizerOptions::
// external_pose_mode): the last external pose taken, carried forward by the clean odometry
// from when it arrived, with its covariance or, without one, the configured sigmas. Under
// kPassThrough it is the estimate while it is recent; under kFuse each one is weighed into one
// filter update.
#pragma once

#include <Eigen/Core>

#include "core/odometry.h"
#include "core/result.h"
#include "vehicle_agent/localization/localizer_options.h"

namespace fleetmap::vehicle_agent {

class ExternalPoseTrack {
 public:
  // Uses external_pose_mode, external_timeout_s, external_sigma_xy_m and
  // external_sigma_theta_rad.
  explicit ExternalPoseTrack(const LocalizerOptions& options);

  // Takes `pose`, which refers to the time the clean odometry was `clean_odom`. Refused (and
  // nothing changes) when invalid or older than the pose taken before (InvalidArgument), or
  // when the mode is kIgnore (FailedPrecondition).
  core::Status Add(const core::PoseEstimate& pose, const core::Pose2& clean_odom);

  enum class Pass {
    kNo,       // not kPassThrough, or no pose taken
    kPassing,  // the pose taken is at most external_timeout_s older than the scan: the estimate
    kLapsed,   // it just timed out (said once per pose taken): the filter takes over from it
  };
  // kPassThrough at a scan stamped `stamp_s`.
  Pass PassThrough(double stamp_s);

  // kFuse and a pose taken since the last TakeFuse.
  bool fuse_due() const;
  // fuse_due(); after it, no pose is due until the next one is taken.
  bool TakeFuse();

  // The pose taken, carried forward by the clean odometry's motion since to `clean_odom_now`.
  core::Pose2 Now(const core::Pose2& clean_odom_now) const;
  // Its covariance, or the sigmas' when a variance is not positive (or no pose was taken).
  Eigen::Matrix3d Covariance() const;

 private:
  const ExternalPoseMode mode_;
  const double timeout_s_;
  const double sigma_xy_m_;
  const double sigma_theta_rad_;
  bool has_ = false;
  bool fresh_ = false;   // taken since the last TakeFuse
  bool lapsed_ = false;  // kPassThrough timed out and the filter took over
  core::PoseEstimate pose_;
  core::Pose2 clean_odom_;  // the clean odometry when it arrived
};

}  // namespace fleetmap::vehicle_agent
