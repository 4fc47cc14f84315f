#include "core/pose2.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::core {
namespace {

TEST(Pose2Test, NormalizeAngleWrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(NormalizeAngle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-0.5 - 4 * M_PI), -0.5, 1e-12);
}

TEST(Pose2Test, ComposeWithInverseIsIdentity) {
  const Pose2 a(1.0, -2.0, 0.7);
  const Pose2 id = a * a.Inverse();
  EXPECT_NEAR(id.x_m, 0.0, 1e-12);
  EXPECT_NEAR(id.y_m, 0.0, 1e-12);
  EXPECT_NEAR(id.theta_rad, 0.0, 1e-12);
}

TEST(Pose2Test, ApplyRotatesThenTranslates) {
  const Pose2 a(1.0, 2.0, M_PI / 2);
  const Eigen::Vector2d p = a.Apply({1.0, 0.0});
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
}

TEST(Pose2Test, MatchesEigenIsometry) {
  const Pose2 a(0.3, -1.2, -2.5), b(4.0, 0.5, 1.9);
  const Pose2 via_eigen = Pose2::FromIsometry(a.ToIsometry() * b.ToIsometry());
  const Pose2 direct = a * b;
  EXPECT_NEAR(via_eigen.x_m, direct.x_m, 1e-12);
  EXPECT_NEAR(via_eigen.y_m, direct.y_m, 1e-12);
  EXPECT_NEAR(via_eigen.theta_rad, direct.theta_rad, 1e-12);
}

TEST(Pose2Test, BetweenGivesTheIncrement) {
  const Pose2 a(1.0, 1.0, 0.5), b(2.0, 3.0, -0.4);
  const Pose2 back = a * Between(a, b);
  EXPECT_NEAR(back.x_m, b.x_m, 1e-12);
  EXPECT_NEAR(back.y_m, b.y_m, 1e-12);
  EXPECT_NEAR(back.theta_rad, b.theta_rad, 1e-12);
}

TEST(Pose2Test, IsFiniteRejectsNan) {
  EXPECT_TRUE(Pose2(1, 2, 3).IsFinite());
  EXPECT_FALSE(Pose2(NAN, 2, 3).IsFinite());
  EXPECT_FALSE(Pose2(1, 2, INFINITY).IsFinite());
}

}  // namespace
}  // namespace fleetmap::core
