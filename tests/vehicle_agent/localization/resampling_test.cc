#include "vehicle_agent/localization/resampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "vehicle_agent/localization/particle_set.h"

namespace fleetmap::vehicle_agent {
namespace {

ParticleSet Weighted(const std::vector<double>& weights) {
  ParticleSet set;
  for (size_t i = 0; i < weights.size(); ++i)
    set.push_back({core::Pose2(double(i), 0, 0), weights[i]});
  return set;
}

TEST(ResamplingTest, LowVarianceCopiesEachParticleInProportionToItsWeight) {
  const ParticleSet set = Weighted({0.5, 0.25, 0.125, 0.125, 0.0});
  std::mt19937 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const ParticleSet out = LowVarianceResample(set, 64, rng);
    ASSERT_EQ(out.size(), 64u);
    std::map<double, int> copies;
    for (const Particle& p : out) {
      ++copies[p.pose.x_m];
      EXPECT_DOUBLE_EQ(p.weight, 1.0 / 64);
    }
    // Exactly count * w, give or take one: the low variance of the sampler.
    EXPECT_NEAR(copies[0.0], 32, 1);
    EXPECT_NEAR(copies[1.0], 16, 1);
    EXPECT_NEAR(copies[2.0], 8, 1);
    EXPECT_EQ(copies.count(4.0), 0u);
  }
  EXPECT_TRUE(LowVarianceResample({}, 10, rng).empty());
}

// A copy is the whole hypothesis: its pose and the odometry scale it holds.
TEST(ResamplingTest, ACopyKeepsItsOdometryScale) {
  ParticleSet set = Weighted({0.5, 0.5});
  set[0].odometry_scale = 0.95, set[1].odometry_scale = 1.04;
  std::mt19937 rng(4);
  for (const Particle& p : LowVarianceResample(set, 16, rng))
    EXPECT_EQ(p.odometry_scale, p.pose.x_m == 0.0 ? 0.95 : 1.04);
}

TEST(ResamplingTest, EffectiveSampleSizeAndNormalisation) {
  ParticleSet uniform = Weighted({1, 1, 1, 1});
  EXPECT_TRUE(NormalizeWeights(uniform));
  EXPECT_DOUBLE_EQ(EffectiveSampleSize(uniform), 4.0);
  ParticleSet one = Weighted({0, 0, 7, 0});
  EXPECT_TRUE(NormalizeWeights(one));
  EXPECT_DOUBLE_EQ(EffectiveSampleSize(one), 1.0);
  ParticleSet dead = Weighted({0, 0, NAN});
  EXPECT_FALSE(NormalizeWeights(dead));  // made uniform
  EXPECT_DOUBLE_EQ(dead[2].weight, 1.0 / 3);
}

TEST(ResamplingTest, KldBoundFollowsFoxsFormula) {
  KldOptions o;
  o.min_particles = 1;
  o.max_particles = 100000;
  EXPECT_EQ(KldParticleCount(1, o), 1);
  // k = 10, epsilon = 0.05, z = 2.326: 9 / 0.1 * (1 - 2/81 + sqrt(2/81) * 2.326)^3.
  const double a = 2.0 / 81.0;
  const double expected = std::ceil(90.0 * std::pow(1 - a + std::sqrt(a) * 2.326, 3));
  EXPECT_EQ(KldParticleCount(10, o), int(expected));
  EXPECT_LT(KldParticleCount(10, o), KldParticleCount(11, o));
  o.min_particles = 200;
  o.max_particles = 3000;
  EXPECT_EQ(KldParticleCount(2, o), 200);
  EXPECT_EQ(KldParticleCount(5000, o), 3000);
}

TEST(ResamplingTest, CountsTheOccupiedBins) {
  const KldOptions o;  // 0.5 m, 0.5 m, 10 deg
  ParticleSet set = {{core::Pose2(0.1, 0.1, 0.0), 1},  {core::Pose2(0.4, 0.2, 0.1), 1},
                     {core::Pose2(0.6, 0.1, 0.0), 1},  {core::Pose2(0.1, 0.1, 0.2), 1},
                     {core::Pose2(-0.1, 0.1, 0.0), 1}, {core::Pose2(1e300, -1e300, 0.0), 1}};
  EXPECT_EQ(CountOccupiedBins(set, o), 5);
}

TEST(ResamplingTest, MomentsAverageHeadingsAcrossTheSeam) {
  ParticleSet set = {{core::Pose2(1.0, 0.0, M_PI - 0.1), 0.5},
                     {core::Pose2(3.0, 2.0, -M_PI + 0.1), 0.5}};
  const PoseMoments m = ComputeMoments(set);
  EXPECT_NEAR(m.mean.x_m, 2.0, 1e-12);
  EXPECT_NEAR(std::abs(m.mean.theta_rad), M_PI, 1e-9);  // not 0
  EXPECT_NEAR(m.covariance(2, 2), 0.01, 1e-9);
  EXPECT_NEAR(m.covariance(0, 1), 1.0, 1e-12);
}

TEST(ResamplingTest, ValidateNamesTheBadField) {
  KldOptions o;
  o.max_particles = 10;
  EXPECT_NE(o.Validate().message().find("KldOptions.max_particles"), std::string::npos);
  o = KldOptions();
  o.epsilon = 0.0;
  EXPECT_NE(o.Validate().message().find("epsilon"), std::string::npos);
  EXPECT_TRUE(KldOptions().Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
