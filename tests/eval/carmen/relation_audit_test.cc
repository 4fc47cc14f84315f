#include "eval/carmen/relation_audit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fleetmap::eval::carmen {
namespace {

// A scan taken at `pose` inside the rectangular room [-4, 6] x [-3, 4], 720 beams over 180 deg.
LaserRecord ScanInRoom(double stamp_s, const core::Pose2& pose) {
  LaserRecord r;
  r.stamp_s = stamp_s;
  r.odom_pose = pose;
  r.scan.angle_min_rad = -M_PI / 2;
  r.scan.angle_increment_rad = M_PI / 720;
  r.scan.range_max_m = 50.0;
  for (int i = 0; i < 720; ++i) {
    const double a = pose.theta_rad + r.scan.angle(i);
    const double dx = std::cos(a), dy = std::sin(a);
    double t = std::numeric_limits<double>::infinity();
    if (dx > 1e-9) t = std::min(t, (6 - pose.x_m) / dx);
    if (dx < -1e-9) t = std::min(t, (-4 - pose.x_m) / dx);
    if (dy > 1e-9) t = std::min(t, (4 - pose.y_m) / dy);
    if (dy < -1e-9) t = std::min(t, (-3 - pose.y_m) / dy);
    r.scan.ranges_m.push_back(static_cast<float>(t));
  }
  return r;
}

TEST(RelationAuditTest, AReferenceOffTheOdometryByWholeStepsIsOnTheLattice) {
  const std::vector<TimedPose> odometry = {
      {1.0, core::Pose2()}, {2.0, core::Pose2(0.5, 0, 0)}, {3.0, core::Pose2(1.0, 0.2, 0.1)}};
  const core::Pose2 odom12 = core::Between(odometry[0].pose, odometry[1].pose);
  const core::Pose2 odom13 = core::Between(odometry[0].pose, odometry[2].pose);
  const std::vector<Relation> relations = {
      {1.0, 2.0, odom12},                                                  // equal
      {1.0, 2.0, core::Pose2(odom12.x_m + 0.10, odom12.y_m, 0)},           // 2 steps
      {1.0, 3.0, core::Pose2(odom13.x_m + 0.05, odom13.y_m - 0.05, 0.1)},  // sqrt(2) steps
      {1.0, 3.0, core::Pose2(odom13.x_m + 0.023, odom13.y_m, 0.1)},        // not whole steps
      {1.0, 9.0, core::Pose2()},                                           // no odometry at 9 s
      {1.0, 100.0, core::Pose2()}};                                        // beyond the span
  const LatticeCheck check = CheckLattice(relations, odometry, 0.05, 0.002, 60.0);
  EXPECT_EQ(check.relations, 4);
  EXPECT_EQ(check.equal_to_odometry, 1);
  EXPECT_EQ(check.on_lattice, 2);
  // With steps of 0.3 m none of the differences (0.023-0.1 m) is a whole number of them.
  EXPECT_EQ(CheckLattice(relations, odometry, 0.3, 0.002, 60.0).on_lattice, 0);
}

TEST(RelationAuditTest, EndPointsDropInvalidReturnsAndTakeTheLaserMount) {
  LaserRecord r;
  r.laser_in_base = core::Pose2(0.04, 0, M_PI / 2);
  r.scan.angle_min_rad = 0;
  r.scan.angle_increment_rad = M_PI / 2;
  r.scan.range_max_m = 50.0;
  r.scan.ranges_m = {2.0f, std::numeric_limits<float>::quiet_NaN(), 0.05f, 50.0f, 30.0f};
  const auto points = EndPointsInBase(r, ScanFitOptions{});
  ASSERT_EQ(points.size(), 1u);             // NaN, too near, no return and beyond 20 m dropped
  EXPECT_NEAR(points[0].x(), 0.04, 1e-12);  // straight ahead of a laser turned left
  EXPECT_NEAR(points[0].y(), 2.0, 1e-12);
}

TEST(RelationAuditTest, TheTrueMotionOverlapsTheScansBetterThanAReferenceFiveCentimetresOff) {
  CarmenLog log;
  const core::Pose2 p1(0, 0, 0), p2(0.5, 0.1, 0.1);
  log.lasers = {ScanInRoom(1.0, p1), ScanInRoom(2.0, p2)};
  const core::Pose2 truth = core::Between(p1, p2);
  const ScanFitOptions options;
  const auto first = EndPointsInBase(log.lasers[0], options);
  const auto second = EndPointsInBase(log.lasers[1], options);
  ASSERT_GT(second.size(), 600u);
  const core::Pose2 off(truth.x_m + 0.05, truth.y_m, truth.theta_rad);
  // At the truth only the beams' spacing along the walls is left (up to 3 cm at 7 m).
  const double at_truth = ScanFit(first, second, truth, options.gate_m);
  EXPECT_LT(at_truth, 0.01);
  EXPECT_GT(ScanFit(first, second, off, options.gate_m), at_truth + 0.01);
  EXPECT_DOUBLE_EQ(ScanFit(first, {}, truth, options.gate_m), options.gate_m);

  const std::vector<TimedPose> estimate = {{1.0, p1}, {2.0, p2}};
  const FitComparison fit = CompareScanFit({{1.0, 2.0, off}}, log, estimate, options);
  EXPECT_EQ(fit.relations, 1);
  EXPECT_EQ(fit.estimate_better, 1);
  EXPECT_EQ(fit.reference_better, 0);
  EXPECT_NEAR(fit.estimate_error_m, 0.05, 1e-9);
  EXPECT_LT(fit.estimate_fit_m, fit.reference_fit_m);
  // An estimate 5 cm off the other way loses to a true reference.
  const std::vector<TimedPose> wrong = {{1.0, p1}, {2.0, p1 * off}};
  EXPECT_EQ(CompareScanFit({{1.0, 2.0, truth}}, log, wrong, options).reference_better, 1);
  // Scans or poses not found by time stamp: not scored.
  EXPECT_EQ(CompareScanFit({{1.0, 2.5, truth}}, log, estimate, options).relations, 0);
}

}  // namespace
}  // namespace fleetmap::eval::carmen
