#include "vehicle_agent/localization/odometry_path.h"

#include <gtest/gtest.h>

namespace fleetmap::vehicle_agent {
namespace {

TEST(OdometryPathTest, KeepsOnePoseEveryStepOfTravelOrTurn) {
  OdometryPath path(0.25, 0.25);
  path.Restart(core::Pose2(1.0, 0.0, 0.0));
  for (int i = 1; i <= 20; ++i) path.Add(core::Pose2(1.0 + 0.05 * i, 0.0, 0.0));  // 1 m
  ASSERT_EQ(path.waypoints().size(), 4u);
  EXPECT_NEAR(path.waypoints()[0].x_m, 1.25, 1e-9);
  EXPECT_NEAR(path.waypoints()[3].x_m, 2.0, 1e-9);
  path.Add(core::Pose2(2.0, 0.0, 0.3));  // a turn on the spot
  EXPECT_EQ(path.waypoints().size(), 5u);
}

TEST(OdometryPathTest, AShortMotionKeepsNoPoseAndRestartForgets) {
  OdometryPath path(0.25, 0.25);
  path.Restart(core::Pose2());
  path.Add(core::Pose2(0.1, 0.0, 0.1));
  EXPECT_TRUE(path.waypoints().empty()) << "one filter update's motion is one increment";
  path.Add(core::Pose2(0.6, 0.0, 0.1));
  EXPECT_EQ(path.waypoints().size(), 1u);
  path.Restart(core::Pose2(0.6, 0.0, 0.1));
  EXPECT_TRUE(path.waypoints().empty());
  path.Add(core::Pose2(0.7, 0.0, 0.1));
  EXPECT_TRUE(path.waypoints().empty()) << "measured from the restart pose";
}

TEST(OdometryPathTest, StopsKeepingPosesAtItsBound) {
  OdometryPath path(0.25, 0.25, 8);
  path.Restart(core::Pose2());
  for (int i = 1; i <= 100; ++i) path.Add(core::Pose2(0.5 * i, 0.0, 0.0));
  EXPECT_EQ(path.waypoints().size(), 8u);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
