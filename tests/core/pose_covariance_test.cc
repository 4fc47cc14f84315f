#include "core/pose_covariance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::core {
namespace {

TEST(PoseCovarianceTest, DiagonalCovarianceSquaresTheSigmas) {
  const Eigen::Matrix3d c = DiagonalCovariance(0.1, 0.2);
  EXPECT_NEAR(c(0, 0), 0.01, 1e-15);
  EXPECT_NEAR(c(1, 1), 0.01, 1e-15);
  EXPECT_NEAR(c(2, 2), 0.04, 1e-15);
  EXPECT_EQ(c(0, 1), 0.0);
  EXPECT_EQ(c(1, 2), 0.0);
}

TEST(PoseCovarianceTest, HeadingsEitherSideOfPiAreClose) {
  const Eigen::Vector3d d = PoseDifference(core::Pose2(1.0, 2.0, 3.1), core::Pose2(0.5, 3.0, -3.1));
  EXPECT_NEAR(d.x(), 0.5, 1e-12);
  EXPECT_NEAR(d.y(), -1.0, 1e-12);
  EXPECT_NEAR(d.z(), 6.2 - 2 * M_PI, 1e-12);
}

TEST(PoseCovarianceTest, MahalanobisDistanceWeighsEachAxisByItsVariance) {
  const Eigen::Matrix3d c = Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal();
  EXPECT_NEAR(SquaredMahalanobis({2.0, 0.0, 0.0}, c), 1.0, 1e-9);
  EXPECT_NEAR(SquaredMahalanobis({0.0, 0.0, 0.5}, c), 1.0, 1e-9);
  EXPECT_NEAR(SquaredMahalanobis({2.0, 1.0, 0.5}, c), 3.0, 1e-9);
  // A singular covariance (a pose known exactly in theta) stays usable: finite, very large.
  const Eigen::Matrix3d singular = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
  const Eigen::Matrix3d information = InformationMatrix(singular);
  EXPECT_TRUE(information.allFinite());
  EXPECT_GT(information(2, 2), 1e11);
  EXPECT_NEAR(information(0, 0), 1.0, 1e-9);
}

}  // namespace
}  // namespace fleetmap::core
