// The vehicle's own localization as the localizer uses it: what is taken, carried forward by
// odometry, passed through while recent, and weighed in once under kFuse.
#include "vehicle_agent/localization/external_pose_track.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::vehicle_agent {
namespace {

using Pass = ExternalPoseTrack::Pass;

LocalizerOptions Options(ExternalPoseMode mode) {
  LocalizerOptions o;
  o.external_pose_mode = mode;
  o.external_timeout_s = 1.0;
  o.external_sigma_xy_m = 0.05;
  o.external_sigma_theta_rad = 0.02;
  return o;
}

core::PoseEstimate Pose(double stamp_s, const core::Pose2& pose,
                        const Eigen::Matrix3d& cov = Eigen::Matrix3d::Zero()) {
  core::PoseEstimate p;
  p.stamp_s = stamp_s;
  p.pose_in_map = pose;
  p.covariance = cov;
  return p;
}

TEST(ExternalPoseTrackTest, APoseIsCarriedForwardByTheOdometryWithItsOrTheConfiguredSigmas) {
  ExternalPoseTrack track(Options(ExternalPoseMode::kPassThrough));
  ASSERT_TRUE(
      track.Add(Pose(10.0, core::Pose2(2.0, 1.0, M_PI / 2)), core::Pose2(5.0, 5.0, 0.0)).ok());
  // The odometry went 1 m straight on since: the vehicle, heading +y in the map, is at y = 2.
  const core::Pose2 now = track.Now(core::Pose2(6.0, 5.0, 0.0));
  EXPECT_NEAR(now.x_m, 2.0, 1e-9);
  EXPECT_NEAR(now.y_m, 2.0, 1e-9);
  EXPECT_NEAR(now.theta_rad, M_PI / 2, 1e-9);
  const Eigen::Matrix3d sigmas = track.Covariance();  // it came without a covariance
  EXPECT_NEAR(sigmas(0, 0), 0.05 * 0.05, 1e-12);
  EXPECT_NEAR(sigmas(2, 2), 0.02 * 0.02, 1e-12);
  EXPECT_EQ(sigmas(0, 1), 0.0);

  const Eigen::Matrix3d own = Eigen::Vector3d(0.04, 0.09, 0.01).asDiagonal();
  ASSERT_TRUE(track.Add(Pose(11.0, core::Pose2(3.0, 1.0, 0.0), own), core::Pose2()).ok());
  EXPECT_TRUE(track.Covariance().isApprox(own));
  EXPECT_NEAR(track.Now(core::Pose2()).x_m, 3.0, 1e-12);
}

TEST(ExternalPoseTrackTest, InvalidOlderOrIgnoredPosesAreRefusedAndChangeNothing) {
  ExternalPoseTrack track(Options(ExternalPoseMode::kFuse));
  ASSERT_TRUE(track.Add(Pose(10.0, core::Pose2(2.0, 1.0, 0.0)), core::Pose2()).ok());
  EXPECT_EQ(track.Add(Pose(9.0, core::Pose2(7.0, 7.0, 0.0)), core::Pose2()).code(),
            core::StatusCode::kInvalidArgument);
  EXPECT_EQ(track.Add(Pose(12.0, core::Pose2(NAN, 7.0, 0.0)), core::Pose2()).code(),
            core::StatusCode::kInvalidArgument);
  EXPECT_NEAR(track.Now(core::Pose2()).x_m, 2.0, 1e-12);

  ExternalPoseTrack ignoring(Options(ExternalPoseMode::kIgnore));
  EXPECT_EQ(ignoring.Add(Pose(10.0, core::Pose2(2.0, 1.0, 0.0)), core::Pose2()).code(),
            core::StatusCode::kFailedPrecondition);
  EXPECT_FALSE(ignoring.fuse_due());
  EXPECT_EQ(ignoring.PassThrough(10.0), Pass::kNo);
}

TEST(ExternalPoseTrackTest, PassesThroughWhileRecentAndSaysOnceWhenItLapsed) {
  ExternalPoseTrack track(Options(ExternalPoseMode::kPassThrough));
  EXPECT_EQ(track.PassThrough(5.0), Pass::kNo);  // none taken
  ASSERT_TRUE(track.Add(Pose(10.0, core::Pose2(2.0, 1.0, 0.0)), core::Pose2()).ok());
  EXPECT_EQ(track.PassThrough(10.5), Pass::kPassing);
  EXPECT_EQ(track.PassThrough(11.0), Pass::kPassing);
  EXPECT_EQ(track.PassThrough(11.5), Pass::kLapsed);
  EXPECT_EQ(track.PassThrough(12.0), Pass::kNo);
  EXPECT_FALSE(track.fuse_due());  // not kFuse
  ASSERT_TRUE(track.Add(Pose(12.0, core::Pose2(2.0, 1.0, 0.0)), core::Pose2()).ok());
  EXPECT_EQ(track.PassThrough(12.5), Pass::kPassing);
  EXPECT_EQ(track.PassThrough(13.5), Pass::kLapsed);  // a new pose can lapse again
}

TEST(ExternalPoseTrackTest, UnderFuseEachPoseIsDueOnce) {
  ExternalPoseTrack track(Options(ExternalPoseMode::kFuse));
  EXPECT_FALSE(track.fuse_due());
  EXPECT_FALSE(track.TakeFuse());
  ASSERT_TRUE(track.Add(Pose(10.0, core::Pose2(2.0, 1.0, 0.0)), core::Pose2()).ok());
  EXPECT_TRUE(track.fuse_due());
  EXPECT_TRUE(track.TakeFuse());
  EXPECT_FALSE(track.fuse_due());
  EXPECT_FALSE(track.TakeFuse());
  EXPECT_EQ(track.PassThrough(10.0), Pass::kNo);  // not kPassThrough
  ASSERT_TRUE(track.Add(Pose(10.5, core::Pose2(2.0, 1.0, 0.0)), core::Pose2()).ok());
  EXPECT_TRUE(track.TakeFuse());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
