#include "vehicle_agent/localization/input_guard.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::vehicle_agent {

OdometryTracker::OdometryTracker(double max_step_m, double max_step_rad, double max_speed_mps,
                                 double max_yaw_rate_radps)
    : max_step_m_(max_step_m),
      max_step_rad_(max_step_rad),
      max_speed_mps_(max_speed_mps),
      max_yaw_rate_radps_(max_yaw_rate_radps) {}

OdometryTracker::Outcome OdometryTracker::Add(const core::OdometrySample& odom) {
  if (!odom.Validate().ok()) return Outcome::kInvalid;
  if (!has_sample_) {
    has_sample_ = true;
    last_ = odom;
    return Outcome::kFirst;
  }
  const bool clock_step = IsClockStepBack(odom.stamp_s, last_.stamp_s);
  if (odom.stamp_s < last_.stamp_s && !clock_step) return Outcome::kOutOfOrder;
  const core::Pose2 step = core::Between(last_.pose_in_odom, odom.pose_in_odom);
  const double gap_s = clock_step ? 0.0 : std::min(odom.stamp_s - last_.stamp_s, kMaxExplainedGapS);
  const double limit_m = std::max(max_step_m_, max_speed_mps_ * gap_s);
  const double limit_rad = std::max(max_step_rad_, max_yaw_rate_radps_ * gap_s);
  last_ = odom;
  if (!step.IsFinite() || std::hypot(step.x_m, step.y_m) > limit_m ||
      std::abs(step.theta_rad) > limit_rad) {
    return Outcome::kJump;
  }
  clean_pose_ = clean_pose_ * step;
  return clock_step ? Outcome::kClockStep : Outcome::kApplied;
}

ScanGate::Outcome ScanGate::Check(const core::LaserScan& scan, const core::Pose2& scanner_in_base) {
  if (!scan.Validate().ok() || !scanner_in_base.IsFinite()) return Outcome::kInvalid;
  const bool clock_step = has_scan_ && IsClockStepBack(scan.stamp_s, last_stamp_s_);
  if (has_scan_ && !(scan.stamp_s > last_stamp_s_) && !clock_step) return Outcome::kOutOfOrder;
  layout_changed_ = has_scan_ && (scan.size() != beams_ || scan.angle_min_rad != angle_min_rad_ ||
                                  scan.angle_increment_rad != angle_increment_rad_);
  has_scan_ = true;
  last_stamp_s_ = scan.stamp_s;
  beams_ = scan.size();
  angle_min_rad_ = scan.angle_min_rad;
  angle_increment_rad_ = scan.angle_increment_rad;
  return clock_step ? Outcome::kClockStep : Outcome::kAccepted;
}

}  // namespace fleetmap::vehicle_agent
