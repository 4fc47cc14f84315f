#include "vehicle_agent/localization/odometry_scale.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::vehicle_agent {
namespace {

TEST(OdometryScaleTest, AnIncrementIsLongerOrShorterNotTurned) {
  const core::Pose2 d = ScaledIncrement(core::Pose2(0.3, 0.4, 0.2), 0.9);
  EXPECT_NEAR(d.x_m, 0.27, 1e-12);
  EXPECT_NEAR(d.y_m, 0.36, 1e-12);
  EXPECT_EQ(d.theta_rad, 0.2);
}

TEST(OdometryScaleTest, ScalesAreDrawnAroundTheCentreWithTheirSpreadAndBounds) {
  ParticleSet particles(4000);
  std::mt19937 rng(3);
  OdometryScaleOptions options;
  options.initial_sigma = 0.05;
  DrawOdometryScales(particles, 1.02, options, rng);
  double sum = 0.0, squares = 0.0;
  for (const Particle& p : particles) {
    sum += p.odometry_scale, squares += p.odometry_scale * p.odometry_scale;
    EXPECT_LE(std::abs(p.odometry_scale - 1.0), options.max_deviation);
  }
  const double mean = sum / particles.size();
  EXPECT_NEAR(mean, 1.02, 0.005);
  EXPECT_NEAR(std::sqrt(squares / particles.size() - mean * mean), 0.05, 0.005);
}

TEST(OdometryScaleTest, WithoutASpreadEveryParticleTrustsTheOdometry) {
  ParticleSet particles(10);
  std::mt19937 rng(3);
  OdometryScaleOptions options;
  options.initial_sigma = 0.0;
  DrawOdometryScales(particles, 1.0, options, rng);
  for (const Particle& p : particles) EXPECT_EQ(p.odometry_scale, 1.0);
}

TEST(OdometryScaleTest, AScaleWandersWithTheSquareRootOfTheDistanceAndStaysInBounds) {
  OdometryScaleOptions options;
  options.walk_sigma_per_sqrt_m = 0.01;
  std::mt19937 rng(5);
  EXPECT_EQ(WalkOdometryScale(1.03, 0.0, options, rng), 1.03);  // standing still
  double squares = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i)
    squares += std::pow(WalkOdometryScale(1.0, 4.0, options, rng) - 1.0, 2);
  EXPECT_NEAR(std::sqrt(squares / n), 0.02, 0.001);  // 0.01 x sqrt(4 m)
  options.walk_sigma_per_sqrt_m = 10.0;
  for (int i = 0; i < 100; ++i)
    EXPECT_LE(std::abs(WalkOdometryScale(1.0, 1.0, options, rng) - 1.0),
              options.max_deviation + 1e-12);
}

TEST(OdometryScaleTest, AScaleIsPulledBackToOneInProportionToTheDistance) {
  OdometryScaleOptions options;
  options.walk_sigma_per_sqrt_m = 0.0;
  options.pull_distance_m = 60.0;
  std::mt19937 rng(5);
  EXPECT_NEAR(WalkOdometryScale(1.1, 30.0, options, rng), 1.05, 1e-12);
  EXPECT_NEAR(WalkOdometryScale(0.9, 6.0, options, rng), 0.91, 1e-12);
  EXPECT_NEAR(WalkOdometryScale(1.1, 600.0, options, rng), 1.0, 1e-12);  // never past 1
  options.pull_distance_m = 0.0;                                         // no pull
  EXPECT_EQ(WalkOdometryScale(1.1, 30.0, options, rng), 1.1);
}

TEST(OdometryScaleTest, TheSetsScaleIsTheWeightedMean) {
  ParticleSet particles(2);
  particles[0].odometry_scale = 0.9, particles[0].weight = 0.75;
  particles[1].odometry_scale = 1.1, particles[1].weight = 0.25;
  EXPECT_NEAR(MeanOdometryScale(particles), 0.95, 1e-12);
}

TEST(OdometryScaleTest, OptionsOutOfRangeAreRefused) {
  OdometryScaleOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.initial_sigma = -0.1;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.walk_sigma_per_sqrt_m = NAN;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.pull_distance_m = -1.0;
  EXPECT_FALSE(o.Validate().ok());
  o.pull_distance_m = INFINITY;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.max_deviation = 0.0;
  EXPECT_FALSE(o.Validate().ok());
  o.max_deviation = 0.6;
  EXPECT_FALSE(o.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
