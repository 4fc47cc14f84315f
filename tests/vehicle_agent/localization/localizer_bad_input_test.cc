// Outside data the localizer must survive: broken ranges, broken scans, time going backwards,
// odometry jumps. Dropped or repaired and counted; never a crash, never a NaN pose.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/vehicle_agent/agent_sim_util.h"

namespace fleetmap::vehicle_agent {
namespace {

using sim_testing::Errors;
using sim_testing::Max;
using sim_testing::Median;
using sim_testing::RunOptions;
using sim_testing::SimRun;
using sim_testing::TranslationError;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// 40 s of the LivingLab route, started 10 cm off, with the inputs damaged by `corrupt`.
SimRun RunDamaged(std::function<void(int, core::OdometrySample&, core::LaserScan&)> corrupt) {
  static const sim::World world = sim_testing::LoadWorld("addition.yaml");
  RunOptions options;
  options.end_s = 40.0;
  options.initial_offset = core::Pose2(0.1, 0.0, 0.02);
  int scan = 0;
  options.corrupt = [&](core::OdometrySample& odom, core::LaserScan& s) {
    corrupt(scan++, odom, s);
  };
  SimRun run = sim_testing::RunVehicle(world, options);
  for (const auto& r : run.scans) {
    EXPECT_TRUE(r.estimate.pose_in_map.IsFinite()) << r.stamp_s;
    EXPECT_TRUE(r.estimate.covariance.allFinite()) << r.stamp_s;
  }
  return run;
}

void ExpectTracking(const SimRun& run, double from_s = 5.0) {
  EXPECT_LT(Median(Errors(run, from_s, 1e9, TranslationError)), 0.05);
  EXPECT_LT(Max(Errors(run, from_s, 1e9, TranslationError)), 0.20);
}

TEST(LocalizerBadInputTest, SkipsNanInfiniteNegativeAndZeroRanges) {
  const SimRun run = RunDamaged([](int, core::OdometrySample&, core::LaserScan& s) {
    for (size_t i = 0; i < s.size(); ++i) {
      if (i % 3 == 0) s.ranges_m[i] = NAN;
      if (i % 7 == 0) s.ranges_m[i] = -1.0f;
      if (i % 11 == 0) s.ranges_m[i] = 0.0f;
      if (i % 13 == 0) s.ranges_m[i] = -INFINITY;
    }
  });
  EXPECT_GT(run.counters.beams_invalid, 250 * static_cast<int64_t>(run.scans.size()));
  ExpectTracking(run);
}

TEST(LocalizerBadInputTest, ScansWithoutAnyReturnLeaveThePoseToOdometry) {
  const SimRun run = RunDamaged([](int, core::OdometrySample&, core::LaserScan& s) {
    if (s.stamp_s >= 20.0 && s.stamp_s < 24.0)
      for (float& r : s.ranges_m) r = NAN;
  });
  EXPECT_GT(run.counters.scans_without_returns, 10);
  for (const auto& r : run.scans) {
    if (r.stamp_s >= 20.0 && r.stamp_s < 24.0) {
      ASSERT_TRUE(std::isnan(r.stats.w_avg)) << r.stamp_s;
      ASSERT_FALSE(r.divergence.accepted) << r.stamp_s;  // the detector skips it
    }
  }
  ExpectTracking(run);
}

TEST(LocalizerBadInputTest, FollowsAScanWithADifferentBeamCount) {
  const SimRun run = RunDamaged([](int, core::OdometrySample&, core::LaserScan& s) {
    if (s.stamp_s < 15.0 || s.stamp_s >= 25.0) return;
    std::vector<float> every_other;  // 271 beams, twice the angle between them
    for (size_t i = 0; i < s.size(); i += 2) every_other.push_back(s.ranges_m[i]);
    s.ranges_m = every_other;
    s.angle_increment_rad *= 2;
  });
  EXPECT_EQ(run.counters.scan_layout_changes, 2);
  ExpectTracking(run);
}

TEST(LocalizerBadInputTest, DropsMalformedScans) {
  const SimRun run = RunDamaged([](int k, core::OdometrySample&, core::LaserScan& s) {
    if (k % 10 == 1) s.angle_increment_rad = 0.0;
    if (k % 10 == 3) s.stamp_s = kNaN;
    if (k % 10 == 5) s.ranges_m.clear();
    if (k % 10 == 7) s.range_max_m = -1.0;
  });
  EXPECT_EQ(run.counters.scans_invalid, 4 * static_cast<int64_t>(run.scans.size() / 10));
  for (const auto& r : run.scans) ASSERT_TRUE(std::isfinite(r.estimate.stamp_s));
  ExpectTracking(run);
}

TEST(LocalizerBadInputTest, DropsScansAndOdometryGoingBackInTime) {
  const SimRun run = RunDamaged([](int k, core::OdometrySample& o, core::LaserScan& s) {
    if (k % 50 == 25) s.stamp_s -= 1.0;
    if (k % 40 == 20) o.stamp_s -= 1.0;
  });
  EXPECT_EQ(run.counters.scans_out_of_order, static_cast<int64_t>((run.scans.size() + 24) / 50));
  EXPECT_GT(run.counters.odometry_out_of_order, 20);
  ExpectTracking(run);
}

TEST(LocalizerBadInputTest, DropsAnOdometryJumpAndKeepsTracking) {
  const SimRun run = RunDamaged([](int, core::OdometrySample& o, core::LaserScan&) {
    if (o.stamp_s >= 15.0) o.pose_in_odom = core::Pose2(100.0, -50.0, 2.0) * o.pose_in_odom;
  });
  EXPECT_EQ(run.counters.odometry_jumps, 1);
  ExpectTracking(run);
}

TEST(LocalizerBadInputTest, DropsNonFiniteOdometry) {
  const SimRun run = RunDamaged([](int k, core::OdometrySample& o, core::LaserScan&) {
    if (k % 30 == 10) o.pose_in_odom.x_m = kNaN;
    if (k % 30 == 20) o.omega_radps = std::numeric_limits<double>::infinity();
  });
  EXPECT_GE(run.counters.odometry_invalid, 2 * static_cast<int64_t>(run.scans.size() / 30));
  ExpectTracking(run);
}

TEST(LocalizerBadInputTest, RefusesBadCallsAndKeepsItsState) {
  Localizer localizer{LocalizerOptions()};
  core::LaserScan scan;
  scan.angle_min_rad = -1.0;
  scan.angle_increment_rad = 0.01;
  scan.range_min_m = 0.05;
  scan.range_max_m = 30.0;
  scan.ranges_m.assign(201, 3.0f);
  // No map yet: the pose is dead reckoning from the configured one, W_avg unknown.
  const LocalizerResult before = localizer.Update({0.0, {}, 0.0, 0.0}, scan, {});
  EXPECT_TRUE(before.estimate.pose_in_map.IsFinite());
  EXPECT_TRUE(std::isnan(before.stats.w_avg));
  EXPECT_EQ(localizer.InitializeGlobal().code(), core::StatusCode::kFailedPrecondition);
  EXPECT_FALSE(localizer.SetMap(core::OccupancyGrid(), 3).ok());
  EXPECT_EQ(localizer.map_version(), -1);
  EXPECT_FALSE(localizer.InitializeAt(core::Pose2(kNaN, 0, 0), Eigen::Matrix3d::Identity()).ok());
  Eigen::Matrix3d asymmetric = Eigen::Matrix3d::Identity();
  asymmetric(0, 1) = 1.0;
  EXPECT_FALSE(localizer.InitializeAt({}, asymmetric).ok());
  EXPECT_FALSE(localizer.InitializeAt({}, -Eigen::Matrix3d::Identity()).ok());
  EXPECT_FALSE(localizer.initialized());
  core::PoseEstimate external;
  external.pose_in_map.x_m = kNaN;
  EXPECT_FALSE(localizer.AddExternalPose(external).ok());
  EXPECT_EQ(localizer.counters().external_poses_dropped, 1);
}

TEST(LocalizerBadInputTest, ValidateNamesTheBadField) {
  LocalizerOptions o;
  o.max_beams = 0;
  EXPECT_NE(o.Validate().message().find("LocalizerOptions.max_beams"), std::string::npos);
  o = LocalizerOptions();
  o.initial_pose_in_map.theta_rad = kNaN;
  EXPECT_NE(o.Validate().message().find("initial_pose_in_map.theta_rad"), std::string::npos);
  o = LocalizerOptions();
  o.kld.min_particles = 0;
  EXPECT_NE(o.Validate().message().find("KldOptions.min_particles"), std::string::npos);
  o = LocalizerOptions();
  o.resample_min_neff_ratio = 1.5;
  EXPECT_NE(o.Validate().message().find("resample_min_neff_ratio"), std::string::npos);
  EXPECT_TRUE(LocalizerOptions().Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
