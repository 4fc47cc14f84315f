#include "eval/tempmap_drift.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::eval {
namespace {

// The vehicle drives along x at 1 m/s turning 0.1 rad/s, starting somewhere in the world.
core::Pose2 TruthAt(double t) { return core::Pose2(4.0, -2.0, 0.7) * core::Pose2(t, 0.0, 0.1 * t); }

std::vector<core::TimedPose> BuiltFromTruth(double from_s, double to_s) {
  std::vector<core::TimedPose> trajectory;
  for (double t = from_s; t <= to_s + 1e-9; t += 0.5)
    trajectory.push_back({t, core::Between(TruthAt(from_s), TruthAt(t))});
  return trajectory;
}

TEST(TempMapDriftTest, ABuilderThatFollowedTheTrueMotionDidNotDrift) {
  const TempMapDrift d = BuilderDrift(BuiltFromTruth(2.0, 5.0), TruthAt);
  EXPECT_NEAR(d.translation_m, 0.0, 1e-9);
  EXPECT_NEAR(d.rotation_deg, 0.0, 1e-9);
}

TEST(TempMapDriftTest, TheLargestErrorOfAnyPoseIsTheDrift) {
  std::vector<core::TimedPose> trajectory = BuiltFromTruth(2.0, 5.0);
  // The frame T of a map need not be the first pose: a map split from the one before goes on
  // in the same frame. Only the motion since the first pose counts.
  for (core::TimedPose& p : trajectory) p.pose = core::Pose2(1.0, 2.0, 0.3) * p.pose;
  trajectory[3].pose = trajectory[3].pose * core::Pose2(0.06, -0.08, 0.0);
  trajectory.back().pose = trajectory.back().pose * core::Pose2(0.0, 0.0, 0.5 * M_PI / 180);
  const TempMapDrift d = BuilderDrift(trajectory, TruthAt);
  EXPECT_NEAR(d.translation_m, 0.10, 1e-9);
  EXPECT_NEAR(d.rotation_deg, 0.5, 1e-9);
}

TEST(TempMapDriftTest, AMapWithoutPosesHasNoDrift) {
  const TempMapDrift d = BuilderDrift({}, TruthAt);
  EXPECT_TRUE(std::isnan(d.translation_m));
  EXPECT_TRUE(std::isnan(d.rotation_deg));
}

}  // namespace
}  // namespace fleetmap::eval
