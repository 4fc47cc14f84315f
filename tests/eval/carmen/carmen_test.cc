#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "eval/carmen/carmen_log.h"
#include "eval/carmen/relations.h"
#include "tests/support/data_dir.h"
#include "vehicle_agent/mapping/local_mapper.h"

namespace fleetmap::eval::carmen {
namespace {

using ::testing::HasSubstr;

TEST(CarmenLogTest, ParsesFlaserRobotLaserAndOdom) {
  CarmenLog log;
  ASSERT_TRUE(
      ParseCarmenLine("FLASER 4 1.0 2.0 50.0 3.5 0 0 0 1.0 2.0 0.5 12.25 host 12.3", 1, {}, log)
          .ok());
  ASSERT_TRUE(ParseCarmenLine("ODOM 1.0 2.0 0.5 0.3 0.1 0 12.5 host 12.5", 2, {}, log).ok());
  ASSERT_TRUE(ParseCarmenLine("ROBOTLASER1 0 -1.5708 3.1416 0.0175 20 0.1 0 3 1 2 3 0 "
                              "1.1 2.0 0.5 1.0 2.0 0.5 0.2 0 0 0 0 13.0 host 13.0",
                              3, {}, log)
                  .ok());
  ASSERT_TRUE(ParseCarmenLine("PARAM robot_length 0.5", 4, {}, log).ok());
  ASSERT_EQ(log.lasers.size(), 2u);
  const LaserRecord& f = log.lasers[0];
  EXPECT_DOUBLE_EQ(f.stamp_s, 12.25);
  EXPECT_NEAR(f.scan.angle_increment_rad, M_PI / 4, 1e-12);  // 4 readings over 180 deg
  EXPECT_FALSE(f.scan.IsValidReturn(2));                     // 50 m = the FLASER "no return"
  EXPECT_DOUBLE_EQ(f.odom_pose.theta_rad, 0.5);
  EXPECT_EQ(log.odometry.size(), 1u);
  EXPECT_DOUBLE_EQ(log.odometry[0].v_mps, 0.3);
  const LaserRecord& r = log.lasers[1];
  EXPECT_EQ(r.scan.size(), 3u);
  EXPECT_NEAR(r.laser_in_base.x_m, 0.1 * std::cos(0.5), 1e-9);  // 10 cm ahead of the base
  EXPECT_EQ(log.skipped_lines, 1);
}

TEST(CarmenLogTest, OdometryIsInterpolatedAtTheScanTime) {
  CarmenLog log;
  ASSERT_TRUE(ParseCarmenLine("ODOM 0 0 0 0 0 0 10.0 h 10.0", 1, {}, log).ok());
  ASSERT_TRUE(ParseCarmenLine("FLASER 2 1 1 0 0 0 0 0 0 10.05 h 10.05", 2, {}, log).ok());
  ASSERT_TRUE(ParseCarmenLine("ODOM 0.1 0 0.2 0 0 0 10.1 h 10.1", 3, {}, log).ok());
  ASSERT_TRUE(ParseCarmenLine("FLASER 2 1 1 0 0 0 0 0 0 10.5 h 10.5", 4, {}, log).ok());
  EXPECT_EQ(InterpolateOdometryAtScans(log), 1);  // the second scan lies after the last ODOM
  EXPECT_NEAR(log.lasers[0].odom_pose.theta_rad, 0.1, 1e-9);
  EXPECT_NEAR(log.lasers[0].odom_pose.x_m, 0.05, 2e-3);  // half way along a slight arc
  EXPECT_EQ(log.lasers[1].odom_pose.x_m, 0.0);           // kept as logged
}

TEST(CarmenLogTest, AScanTakenBeforeItsStampReadsTheOdometryThen) {
  CarmenLog log;
  ASSERT_TRUE(ParseCarmenLine("ODOM 0 0 0 0 0 0 10.0 h 10.0", 1, {}, log).ok());
  ASSERT_TRUE(ParseCarmenLine("ODOM 0.2 0 0 0 0 0 10.2 h 10.2", 2, {}, log).ok());
  ASSERT_TRUE(ParseCarmenLine("FLASER 2 1 1 0 0 0 0 0 0 10.15 h 10.15", 3, {}, log).ok());
  ASSERT_TRUE(ParseCarmenLine("FLASER 2 1 1 0 0 0 0 0 0 10.25 h 10.25", 4, {}, log).ok());
  EXPECT_EQ(InterpolateOdometryAtScans(log, 0.1), 2);  // read at 10.05 and 10.15
  EXPECT_NEAR(log.lasers[0].odom_pose.x_m, 0.05, 1e-9);
  EXPECT_NEAR(log.lasers[1].odom_pose.x_m, 0.15, 1e-9);
  EXPECT_EQ(InterpolateOdometryAtScans(log, std::nan("")), 0);  // refused, poses kept
  EXPECT_NEAR(log.lasers[1].odom_pose.x_m, 0.15, 1e-9);
}

TEST(CarmenLogTest, MalformedLinesNameTheirNumber) {
  CarmenLog log;
  EXPECT_THAT(ParseCarmenLine("FLASER 3 1.0 2.0", 7, {}, log).message(), HasSubstr("line 7"));
  EXPECT_FALSE(ParseCarmenLine("FLASER 99999999 1", 8, {}, log).ok());
  EXPECT_FALSE(ParseCarmenLine("ODOM 1 2 nan 0 0 0 1 h 1", 9, {}, log).ok());
  EXPECT_FALSE(ParseCarmenLine("FLASER -2 0 0 0 0 0 0 1 h 1", 10, {}, log).ok());
  EXPECT_TRUE(log.lasers.empty());
}

TEST(RelationsTest, PerfectTrajectoryScoresZeroAndAnOffsetShows) {
  const std::vector<Relation> relations = {{1.0, 2.0, core::Pose2(1, 0, 0.1)},
                                           {2.0, 3.0, core::Pose2(0, 1, 0)},
                                           {1.0, 100.0, core::Pose2(5, 5, 0)}};
  std::vector<TimedPose> t = {{1.0, core::Pose2()}, {2.0, core::Pose2(1, 0, 0.1)}};
  t.push_back({3.0, t[1].pose * core::Pose2(0, 1, 0)});
  const RelationErrors short_span = ScoreRelations(relations, t, 60.0);
  EXPECT_EQ(short_span.used, 2);
  EXPECT_NEAR(short_span.trans_mean_m, 0.0, 1e-12);
  const RelationErrors all = ScoreRelations(relations, t);
  EXPECT_EQ(all.missing, 1);                       // t = 100 is not in the trajectory
  t[2].pose = t[1].pose * core::Pose2(0.1, 1, 0);  // 10 cm off
  EXPECT_NEAR(ScoreRelations(relations, t).trans_mean_m, 0.05, 1e-9);
}

// A log whose stamps are not those its relations were made from (mit-killian's are rewritten)
// scores no relation: an error naming both time ranges, never means of 0 over nothing.
TEST(RelationsTest, NoRelationScoredIsAnErrorWithBothTimeRanges) {
  const std::vector<Relation> relations = {{500.0, 501.0, core::Pose2(1, 0, 0)},
                                           {501.0, 590.0, core::Pose2(2, 0, 0)}};
  const std::vector<TimedPose> t = {{1.0, core::Pose2()}, {2.0, core::Pose2(1, 0, 0)}};
  const RelationErrors e = ScoreRelations(relations, t);
  EXPECT_EQ(e.used, 0);
  EXPECT_EQ(e.missing, 2);
  EXPECT_DOUBLE_EQ(e.missing_share(), 1.0);
  const core::Status s = CheckScored(e, relations, t);
  EXPECT_EQ(s.code(), core::StatusCode::kNotFound);
  EXPECT_THAT(s.message(), ::testing::HasSubstr("2 relations"));
  EXPECT_THAT(s.message(), ::testing::HasSubstr("relations from 500.000 to 590.000 s"));
  EXPECT_THAT(s.message(), ::testing::HasSubstr("trajectory from 1.000 to 2.000 s (2 poses)"));
  // Within a 60 s span one relation is in reach and missing; with no relation in the span
  // the share itself is undefined.
  EXPECT_FALSE(CheckScored(ScoreRelations(relations, t, 60.0), relations, t, 60.0).ok());
  EXPECT_TRUE(std::isnan(ScoreRelations(relations, t, 0.5).missing_share()));
  EXPECT_FALSE(CheckScored(ScoreRelations(relations, {}), relations, {}).ok());
  // One relation scored of two: OK, and half missing.
  const std::vector<TimedPose> half = {{500.0, core::Pose2()}, {501.0, core::Pose2(1, 0, 0)}};
  const RelationErrors some = ScoreRelations(relations, half);
  EXPECT_TRUE(CheckScored(some, relations, half).ok());
  EXPECT_DOUBLE_EQ(some.missing_share(), 0.5);
}

TEST(RelationsTest, TheNearestTimeStampIsUsedNotTheFirstWithinTolerance) {
  // intel's scans come in bursts: two scans 0.9 ms apart are a scan period of motion apart.
  const std::vector<Relation> relations = {{10.0, 11.0, core::Pose2(1, 0, 0)}};
  const std::vector<TimedPose> t = {{9.9991, core::Pose2(0.5, 0, 0)},
                                    {10.0, core::Pose2()},
                                    {11.0, core::Pose2(1, 0, 0)},
                                    {11.0009, core::Pose2(1.5, 0, 0)}};
  const RelationErrors e = ScoreRelations(relations, t);
  EXPECT_EQ(e.used, 1);
  EXPECT_NEAR(e.trans_mean_m, 0.0, 1e-12);
  EXPECT_EQ(ScoreRelations({{10.002, 11.0, core::Pose2()}}, t).missing, 1);  // none within 1 ms
}

// The real intel log (Kuemmerle et al.'s benchmark): over its first 3000 scans the scan
// matcher must beat the log's own odometry within 60 s, in translation and rotation.
TEST(RealLogTest, ScanMatcherBeatsOdometryOnIntel) {
  FLEETMAP_SKIP_WITHOUT_DATA("real/intel/intel.rebuilt.clf");
  const std::string dir = testing::DataPath("real/intel/");
  auto log = ReadCarmenLog(dir + "intel.rebuilt.clf");
  ASSERT_TRUE(log.ok()) << log.status().ToString();
  auto relations = ReadRelations(dir + "intel.relations");
  ASSERT_TRUE(relations.ok());
  EXPECT_EQ(log->lasers.size(), 13631u);
  vehicle_agent::LocalMapperOptions options;
  options.map.size_m = 60;
  vehicle_agent::LocalMapper mapper(options, log->lasers[0].odom_pose);
  std::vector<TimedPose> matched, odometry;
  for (size_t i = 0; i < 3000; ++i) {
    const LaserRecord& r = log->lasers[i];
    const core::Pose2 delta =
        i ? core::Between(log->lasers[i - 1].odom_pose, r.odom_pose) : core::Pose2();
    mapper.AddScan(r.scan, delta, r.laser_in_base);
    matched.push_back({r.stamp_s, mapper.pose()});
    odometry.push_back({r.stamp_s, r.odom_pose});
  }
  const RelationErrors ours = ScoreRelations(*relations, matched, 60.0);
  const RelationErrors odom = ScoreRelations(*relations, odometry, 60.0);
  ASSERT_GT(ours.used, 200);
  EXPECT_LT(ours.trans_mean_m, odom.trans_mean_m);
  EXPECT_LT(ours.rot_mean_deg, 0.6);
  EXPECT_LT(ours.rot_mean_deg, odom.rot_mean_deg / 2);
}

}  // namespace
}  // namespace fleetmap::eval::carmen
