#include "eval/anchor_consistency.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::eval {
namespace {

Eigen::Matrix3d Diagonal(double sigma_xy_m, double sigma_theta_rad) {
  return Eigen::Vector3d(sigma_xy_m * sigma_xy_m, sigma_xy_m * sigma_xy_m,
                         sigma_theta_rad * sigma_theta_rad)
      .asDiagonal();
}

TEST(AnchorConsistencyTest, AnErrorOfOneSigmaInEachAxisScoresThree) {
  const core::Pose2 truth(10.0, 5.0, 0.5);
  const core::Pose2 anchor(10.0 - 0.02, 5.0 + 0.02, 0.5 - 0.01);
  EXPECT_NEAR(AnchorNees(anchor, Diagonal(0.02, 0.01), truth), 3.0, 1e-6);
}

TEST(AnchorConsistencyTest, TheSameErrorScoresMoreAgainstAnOverconfidentCovariance) {
  const core::Pose2 truth(1.0, 2.0, 0.0), anchor(1.1, 2.0, 0.0);
  EXPECT_NEAR(AnchorNees(anchor, Diagonal(0.1, 0.01), truth), 1.0, 1e-6);
  EXPECT_NEAR(AnchorNees(anchor, Diagonal(0.01, 0.01), truth), 100.0, 1e-6);
}

TEST(AnchorConsistencyTest, TheHeadingErrorIsWrappedAcrossPi) {
  const core::Pose2 truth(0.0, 0.0, M_PI - 0.01), anchor(0.0, 0.0, -M_PI + 0.01);
  EXPECT_NEAR(AnchorNees(anchor, Diagonal(1.0, 0.02), truth), 1.0, 1e-6);
}

TEST(AnchorConsistencyTest, ACorrelationTurnsTheErrorIntoLessSurprise) {
  Eigen::Matrix3d c = Diagonal(0.1, 0.1);
  c(0, 1) = c(1, 0) = 0.009;  // x and y err together (correlation 0.9)
  const core::Pose2 truth(0.1, 0.1, 0.0), anchor(0.0, 0.0, 0.0);
  EXPECT_LT(AnchorNees(anchor, c, truth), AnchorNees(anchor, Diagonal(0.1, 0.1), truth));
}

TEST(AnchorConsistencyTest, ACovarianceThatClaimsCertaintyMakesAnyErrorEnormous) {
  EXPECT_GT(AnchorNees({}, Eigen::Matrix3d::Zero(), core::Pose2(0.01, 0.0, 0.0)), 1e6);
}

}  // namespace
}  // namespace fleetmap::eval
