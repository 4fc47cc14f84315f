// What OdometryTracker takes as motion and what as a jump.
#include "vehicle_agent/localization/input_guard.h"

#include <gtest/gtest.h>

namespace fleetmap::vehicle_agent {
namespace {

using Outcome = OdometryTracker::Outcome;

core::OdometrySample At(double stamp_s, double x_m, double theta_rad = 0.0) {
  core::OdometrySample s;
  s.stamp_s = stamp_s;
  s.pose_in_odom = core::Pose2(x_m, 0.0, theta_rad);
  return s;
}

TEST(OdometryTrackerTest, TakesAStepTheGapBetweenSamplesExplains) {
  OdometryTracker tracker(1.0, 1.0, 4.0, 3.0);
  ASSERT_EQ(tracker.Add(At(10.0, 0.0)), Outcome::kFirst);
  // 1 s without samples (lost on the way) at 2 m/s: a 2 m step, more than max_step_m.
  EXPECT_EQ(tracker.Add(At(11.0, 2.0)), Outcome::kApplied);
  EXPECT_NEAR(tracker.clean_pose().x_m, 2.0, 1e-12);
  // Turning 2 rad in the next second too.
  EXPECT_EQ(tracker.Add(At(12.0, 2.0, 2.0)), Outcome::kApplied);
  EXPECT_NEAR(tracker.clean_pose().theta_rad, 2.0, 1e-12);
}

TEST(OdometryTrackerTest, RefusesAStepTooFastForItsGap) {
  OdometryTracker tracker(1.0, 1.0, 4.0, 3.0);
  tracker.Add(At(10.0, 0.0));
  EXPECT_EQ(tracker.Add(At(10.02, 2.0)), Outcome::kJump);      // 100 m/s: an odometry reset
  EXPECT_EQ(tracker.Add(At(10.04, 2.01)), Outcome::kApplied);  // the jump became the reference
  EXPECT_NEAR(tracker.clean_pose().x_m, 0.01, 1e-12);
  EXPECT_EQ(tracker.Add(At(10.06, 2.01, 1.5)), Outcome::kJump);  // 75 rad/s
}

TEST(OdometryTrackerTest, ALongOutageExplainsNoMoreThanFiveSeconds) {
  OdometryTracker tracker(1.0, 1.0, 4.0, 3.0);
  tracker.Add(At(0.0, 0.0));
  // 60 s of silence, then the frame 30 m away: a reset, not 0.5 m/s of driving.
  EXPECT_EQ(tracker.Add(At(60.0, 30.0)), Outcome::kJump);
  EXPECT_NEAR(tracker.clean_pose().x_m, 0.0, 1e-12);
}

TEST(OdometryTrackerTest, WithoutSpeedsOnlyTheFixedStepHolds) {
  OdometryTracker tracker(1.0, 1.0);
  tracker.Add(At(10.0, 0.0));
  EXPECT_EQ(tracker.Add(At(11.0, 2.0)), Outcome::kJump);
  EXPECT_EQ(tracker.Add(At(12.0, 2.9)), Outcome::kApplied);
}

TEST(OdometryTrackerTest, AClockSetBackExplainsNothing) {
  OdometryTracker tracker(1.0, 1.0, 4.0, 3.0);
  tracker.Add(At(100.0, 0.0));
  EXPECT_EQ(tracker.Add(At(50.0, 0.5)), Outcome::kClockStep);
  EXPECT_EQ(tracker.Add(At(51.0, 2.5)), Outcome::kApplied);  // 2 m in 1 s after the step
  EXPECT_EQ(tracker.Add(At(10.0, 4.5)), Outcome::kJump);     // back again, and 2 m at once
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
