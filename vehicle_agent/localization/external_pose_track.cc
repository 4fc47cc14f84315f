#include "vehicle_agent/localization/external_pose_track.h"

#include "core/pose_covariance.h"

namespace fleetmap::vehicle_agent {

ExternalPoseTrack::ExternalPoseTrack(const LocalizerOptions& options)
    : mode_(options.external_pose_mode),
      timeout_s_(options.external_timeout_s),
      sigma_xy_m_(options.external_sigma_xy_m),
      sigma_theta_rad_(options.external_sigma_theta_rad) {}

core::Status ExternalPoseTrack::Add(const core::PoseEstimate& pose, const core::Pose2& clean_odom) {
  core::Status status = pose.Validate();
  if (status.ok() && has_ && pose.stamp_s < pose_.stamp_s)
    status = core::InvalidArgument("external pose older than the previous one");
  if (status.ok() && mode_ == ExternalPoseMode::kIgnore)
    status = core::FailedPrecondition("external poses are ignored (external_pose_mode)");
  if (!status.ok()) return status;
  pose_ = pose;
  clean_odom_ = clean_odom;
  has_ = fresh_ = true;
  lapsed_ = false;
  return core::OkStatus();
}

ExternalPoseTrack::Pass ExternalPoseTrack::PassThrough(double stamp_s) {
  if (mode_ != ExternalPoseMode::kPassThrough || !has_) return Pass::kNo;
  if (stamp_s - pose_.stamp_s <= timeout_s_) return Pass::kPassing;
  if (lapsed_) return Pass::kNo;
  lapsed_ = true;
  return Pass::kLapsed;
}

bool ExternalPoseTrack::fuse_due() const { return mode_ == ExternalPoseMode::kFuse && fresh_; }

bool ExternalPoseTrack::TakeFuse() {
  const bool due = fuse_due();
  fresh_ = false;
  return due;
}

core::Pose2 ExternalPoseTrack::Now(const core::Pose2& clean_odom_now) const {
  return pose_.pose_in_map * core::Between(clean_odom_, clean_odom_now);
}

Eigen::Matrix3d ExternalPoseTrack::Covariance() const {
  const Eigen::Matrix3d& c = pose_.covariance;
  if (c(0, 0) > 0 && c(1, 1) > 0 && c(2, 2) > 0) return c;
  return core::DiagonalCovariance(sigma_xy_m_, sigma_theta_rad_);
}

}  // namespace fleetmap::vehicle_agent
