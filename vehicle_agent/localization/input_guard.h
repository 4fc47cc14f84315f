// What the localizer lets through from its inputs. Outside data is never trusted: odometry
// with NaNs, going back in time or jumping (an odometry reset, a glitch) and scans that are
// malformed or out of order are dropped and counted, never applied and never a crash.
#pragma once

#include <cstddef>

#include "core/odometry.h"
#include "core/scan.h"

namespace fleetmap::vehicle_agent {

// A stamp more than this before the last one is the vehicle's clock being set back (an NTP
// step, a controller rebooted without a real-time clock), not a late message, s: it becomes
// the new reference. Dropping it as out of order would stop localization until the clock
// caught up again, an hour for an hour's step (tests/vehicle_agent/node/clock_jump_test.cc).
constexpr double kClockStepBackS = 2.0;

// True when `stamp_s` is the clock set back from `last_s` (see kClockStepBackS).
inline bool IsClockStepBack(double stamp_s, double last_s) {
  return stamp_s < last_s - kClockStepBackS;
}

// Composes the accepted odometry increments into a "clean" odometry pose: the odometry frame
// with every dropped increment cut out. Poses derived from it never see a jump.
class OdometryTracker {
 public:
  // kClockStep: applied, though its stamp is kClockStepBackS or more before the last one.
  enum class Outcome { kFirst, kApplied, kInvalid, kOutOfOrder, kJump, kClockStep };

  // The largest believable increment between two samples: max_step_m / max_step_rad, or
  // what max_speed_mps / max_yaw_rate_radps cover in the time between their stamps (up to
  // kMaxExplainedGapS), so that samples lost on the way (a CAN or network gap) do not turn
  // the motion in the gap into a jump. 0 speeds: the fixed steps only.
  OdometryTracker(double max_step_m, double max_step_rad, double max_speed_mps = 0.0,
                  double max_yaw_rate_radps = 0.0);

  // A jump is dropped but becomes the new reference, so the samples after it apply again.
  Outcome Add(const core::OdometrySample& odom);

  bool has_sample() const { return has_sample_; }
  const core::OdometrySample& last() const { return last_; }
  // Starts at the identity when the first sample arrives.
  const core::Pose2& clean_pose() const { return clean_pose_; }

 private:
  // A longer gap is not taken as motion: an odometry reset after an outage stays a jump.
  static constexpr double kMaxExplainedGapS = 5.0;

  double max_step_m_, max_step_rad_, max_speed_mps_, max_yaw_rate_radps_;
  bool has_sample_ = false;
  core::OdometrySample last_;
  core::Pose2 clean_pose_;
};

// Accepts scans whose header validates (LaserScan::Validate), whose scanner mount is finite
// and whose stamp is later than the last accepted one (or a clock step back); notes when the
// beam layout changes.
class ScanGate {
 public:
  // kClockStep: accepted, though its stamp is kClockStepBackS or more before the last one.
  enum class Outcome { kAccepted, kInvalid, kOutOfOrder, kClockStep };

  Outcome Check(const core::LaserScan& scan, const core::Pose2& scanner_in_base);
  // The last accepted scan had a different beam count or angles than the one before.
  bool layout_changed() const { return layout_changed_; }
  bool has_scan() const { return has_scan_; }
  double last_stamp_s() const { return last_stamp_s_; }  // 0 before the first scan

 private:
  bool has_scan_ = false;
  bool layout_changed_ = false;
  double last_stamp_s_ = 0.0;
  size_t beams_ = 0;
  double angle_min_rad_ = 0.0, angle_increment_rad_ = 0.0;
};

}  // namespace fleetmap::vehicle_agent
