#include "vehicle_agent/localization/motion_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace fleetmap::vehicle_agent {
namespace {

struct Spread {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(), sd = Eigen::Vector3d::Zero();
};

// Mean and standard deviation of n samples of the pose after `delta` from the origin.
Spread Sample(const core::Pose2& delta, const MotionModelOptions& o, int n = 4000) {
  std::mt19937 rng(3);
  std::vector<Eigen::Vector3d> poses;
  Spread s;
  for (int i = 0; i < n; ++i) {
    const core::Pose2 p = SampleMotionModelOdometry({}, delta, o, rng);
    poses.emplace_back(p.x_m, p.y_m, core::NormalizeAngle(p.theta_rad - delta.theta_rad));
    s.mean += poses.back() / n;
  }
  for (const auto& p : poses) s.sd += (p - s.mean).cwiseAbs2() / n;
  s.sd = s.sd.cwiseSqrt();
  s.mean.z() += delta.theta_rad;
  return s;
}

MotionModelOptions Noiseless() {
  MotionModelOptions o;
  o.alpha1_rot_from_rot = o.alpha2_rot_from_trans = o.alpha3_trans_from_trans = 0.0;
  o.alpha4_trans_from_rot = o.alpha5_lateral_from_trans = 0.0;
  return o;
}

TEST(MotionModelTest, WithoutNoiseItComposesTheIncrement) {
  std::mt19937 rng(1);
  const core::Pose2 start(2.0, 1.0, 0.5), delta(0.3, 0.1, -0.2);
  const core::Pose2 end = SampleMotionModelOdometry(start, delta, Noiseless(), rng);
  const core::Pose2 expected = start * delta;
  EXPECT_NEAR(end.x_m, expected.x_m, 1e-12);
  EXPECT_NEAR(end.y_m, expected.y_m, 1e-12);
  EXPECT_NEAR(end.theta_rad, expected.theta_rad, 1e-12);
}

TEST(MotionModelTest, NoiseGrowsWithTheMotionAsTheAlphasSay) {
  MotionModelOptions o = Noiseless();
  o.alpha3_trans_from_trans = 0.01;      // sd 10% of the distance along the way
  o.alpha5_lateral_from_trans = 0.0025;  // sd 5% sideways
  const Spread s = Sample({1.0, 0.0, 0.0}, o);
  EXPECT_NEAR(s.mean.x(), 1.0, 0.01);
  EXPECT_NEAR(s.sd.x(), 0.1, 0.01);
  EXPECT_NEAR(s.sd.y(), 0.05, 0.005);
  EXPECT_NEAR(s.sd.z(), 0.0, 1e-12);
  o = Noiseless();
  o.alpha1_rot_from_rot = 0.01;  // sd 10% of the turn
  const Spread turn = Sample({0.0, 0.0, 1.0}, o);
  EXPECT_NEAR(turn.mean.z(), 1.0, 0.01);
  EXPECT_NEAR(turn.sd.z(), 0.1, 0.01);
  EXPECT_NEAR(turn.sd.x(), 0.0, 1e-12);
  const Spread still = Sample({0.0, 0.0, 0.0}, MotionModelOptions());
  EXPECT_EQ(still.sd, Eigen::Vector3d::Zero());
}

// Reversing 5 cm is a small motion, not a half turn with half-turn-sized heading noise.
TEST(MotionModelTest, ReversingDoesNotSpreadTheHeadingByHalfATurn) {
  const Spread back = Sample({-0.05, 0.0, 0.0}, MotionModelOptions());
  EXPECT_NEAR(back.mean.x(), -0.05, 0.002);
  EXPECT_LT(back.sd.z(), 0.01);
  EXPECT_LT(back.sd.y(), 0.01);
}

TEST(MotionModelTest, ValidateNamesTheBadField) {
  MotionModelOptions o;
  o.alpha3_trans_from_trans = -0.1;
  EXPECT_NE(o.Validate().message().find("MotionModelOptions.alpha3_trans_from_trans"),
            std::string::npos);
  o = MotionModelOptions();
  o.alpha5_lateral_from_trans = INFINITY;
  EXPECT_NE(o.Validate().message().find("alpha5_lateral_from_trans"), std::string::npos);
  EXPECT_TRUE(MotionModelOptions().Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
