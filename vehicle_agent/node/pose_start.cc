#include "vehicle_agent/node/pose_start.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "lcmtypes/channels.h"

namespace fleetmap::vehicle_agent::node {
namespace {

// The covariance of an external pose, or the localizer's sigmas when it has none.
Eigen::Matrix3d ExternalCovariance(const core::PoseEstimate& pose, const LocalizerOptions& o) {
  const Eigen::Vector3d d = pose.covariance.diagonal();
  if (pose.covariance.allFinite() && d.minCoeff() > 0.0) return pose.covariance;
  return Eigen::Vector3d(o.external_sigma_xy_m * o.external_sigma_xy_m,
                         o.external_sigma_xy_m * o.external_sigma_xy_m,
                         o.external_sigma_theta_rad * o.external_sigma_theta_rad)
      .asDiagonal();
}

}  // namespace

PoseStart::PoseStart(const AgentNodeOptions& options, AgentPipeline* pipeline, CauseLog* log,
                     MessageChecks* checks, AgentNodeCounters* counters)
    : options_(options),
      pipeline_(pipeline),
      log_(log),
      checks_(checks),
      counters_(counters),
      poses_(options.outbox.state_dir) {}

void PoseStart::LoadKept() {
  if (!(options_.last_pose.period_s > 0) ||
      options_.initial_pose == InitialPoseSource::kFirstExternal)
    return;
  core::Result<KeptPose> kept = poses_.Load();
  if (kept.ok()) {
    kept_pose_ = *kept;
  } else if (kept.status().code() != core::StatusCode::kNotFound) {
    log_->Warning("last pose not used: " + kept.status().ToString());
  }
}

void PoseStart::OnFirstMap() {
  map_in_use_ = true;
  // A kept pose waits for the first odometry sample, which tells whether it still holds.
  initialized_ = options_.initial_pose != InitialPoseSource::kFirstExternal && !kept_pose_;
  if (early_external_) InitializeFromExternal(*early_external_);
}

void PoseStart::OnOdometry(const core::Pose2& odometry) {
  odometry_ = odometry;
  if (kept_pose_) ResumeFromKeptPose(odometry);
}

void PoseStart::OnExternalPose(const core::PoseEstimate& pose) {
  if (!map_in_use_) {
    early_external_ = pose;
    return;
  }
  if (!initialized_) return InitializeFromExternal(pose);
  (void)pipeline_->AddExternalPose(pose);  // the localizer counts what it refuses
}

void PoseStart::InitializeFromExternal(const core::PoseEstimate& pose) {
  early_external_.reset();
  if (options_.initial_pose != InitialPoseSource::kFirstExternal || initialized_) return;
  const core::Status s = pipeline_->InitializeAt(
      pose.pose_in_map, ExternalCovariance(pose, options_.pipeline.localizer));
  if (!s.ok()) {
    checks_->Malformed(lcmtypes::ExternalPoseChannel(options_.pipeline.vehicle_id), s);
    return;
  }
  initialized_ = true;
  log_->Info("initial pose from the external localization");
}

void PoseStart::ResumeFromKeptPose(const core::Pose2& odometry) {
  const KeptPose kept = *kept_pose_;
  kept_pose_.reset();
  if (map_in_use_) initialized_ = true;
  if (!StillThere(kept, odometry, options_.last_pose)) {
    const core::Pose2 moved = core::Between(kept.odometry, odometry);
    char text[160];
    std::snprintf(text, sizeof(text),
                  "last pose not used: the odometry moved %.2f m, %.3f rad since it was kept; ",
                  std::hypot(moved.x_m, moved.y_m), moved.theta_rad);
    log_->Info(text + std::string(options_.initial_pose == InitialPoseSource::kGlobal
                                      ? "searching the whole map"
                                      : "starting from the given pose"));
    return;
  }
  const LocalizerOptions& l = options_.pipeline.localizer;
  const Eigen::Matrix3d around =
      Eigen::Vector3d(l.global_sigma_xy_m, l.global_sigma_xy_m, l.global_sigma_theta_rad)
          .cwiseAbs2()
          .asDiagonal();
  const core::Status s = pipeline_->InitializeAt(kept.base_in_map, around);
  if (!s.ok()) {
    log_->Warning("last pose not used: " + s.ToString());
    return;
  }
  ++counters_->starts_from_last_pose;
  log_->Info("starting from the last pose kept in " + poses_.path() +
             ": the vehicle has not moved since");
}

void PoseStart::OnStep(const AgentStep& step, double now_s) {
  KeepPose(step, now_s, /*now=*/false);
  last_step_ = step;
}

void PoseStart::KeepLast(double now_s) {
  if (last_step_) KeepPose(*last_step_, now_s, /*now=*/true);
}

void PoseStart::KeepPose(const AgentStep& step, double now_s, bool now) {
  if (!poses_.enabled() || !(options_.last_pose.period_s > 0) || !odometry_) return;
  if (!now && now_s < next_keep_s_) return;
  if (!step.well_localized) return;  // only a pose worth starting from
  if (last_kept_ && StillThere(*last_kept_, *odometry_, options_.last_pose)) return;
  const KeptPose kept{step.pose.pose_in_map, *odometry_, step.pose.map_version};
  next_keep_s_ = now_s + options_.last_pose.period_s;
  const core::Status stored = poses_.Store(kept);
  if (!stored.ok()) {
    log_->Once("last pose", "cannot keep the last pose: " + stored.ToString());
    return;
  }
  last_kept_ = kept;
}

}  // namespace fleetmap::vehicle_agent::node
