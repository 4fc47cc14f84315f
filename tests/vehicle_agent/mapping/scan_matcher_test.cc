#include "vehicle_agent/mapping/scan_matcher.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/map/ray_caster.h"
#include "vehicle_agent/mapping/local_mapper.h"

namespace fleetmap::vehicle_agent {
namespace {

// A 8 m x 6 m room with a box, drawn into a multi-resolution map by simulated scans from a
// known pose; then a scan from `truth` is matched starting from a wrong prediction.
class ScanMatcherTest : public ::testing::Test {
 protected:
  void SetUp() override {
    world_ = core::OccupancyGrid(core::GridGeometry(0.05, 160, 120, core::Pose2(-4, -3, 0)));
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        const bool wall = x == 0 || y == 0 || x == 159 || y == 119;
        const bool box = x >= 100 && x < 110 && y >= 30 && y < 50;
        world_.SetState({x, y}, wall || box ? core::CellState::kOccupied : core::CellState::kFree);
      }
  }

  core::LaserScan ScanFrom(const core::Pose2& pose, const core::OccupancyGrid& world) const {
    core::RayCaster caster(world.geometry());
    std::vector<uint8_t> solid(world.cells().size());
    for (size_t i = 0; i < solid.size(); ++i) solid[i] = world.cells()[i] > 0;
    caster.SetSolid(solid);
    core::LaserScan scan;
    scan.angle_min_rad = -3 * M_PI / 4;
    scan.angle_increment_rad = M_PI / 360;
    scan.range_min_m = 0.05;
    scan.range_max_m = 30;
    for (int i = 0; i < 541; ++i) {
      const double r = caster.Cast(pose.translation(), pose.theta_rad + scan.angle(i), 30).range_m;
      scan.ranges_m.push_back(std::isfinite(r) ? float(r) : INFINITY);
    }
    return scan;
  }

  std::vector<Eigen::Vector2d> Points(const core::LaserScan& scan) const {
    std::vector<Eigen::Vector2d> p;
    for (size_t i = 0; i < scan.size(); ++i)
      if (scan.IsValidReturn(i))
        p.push_back(scan.ranges_m[i] *
                    Eigen::Vector2d(std::cos(scan.angle(i)), std::sin(scan.angle(i))));
    return p;
  }

  MultiResolutionMap MapFrom(const std::vector<core::Pose2>& poses,
                             const core::OccupancyGrid& world, double size_m = 12) const {
    MultiResolutionMapOptions o;
    o.size_m = size_m;
    MultiResolutionMap map(o);
    for (const core::Pose2& p : poses) map.Insert(ScanFrom(p, world), p);
    return map;
  }

  core::OccupancyGrid world_;
};

TEST_F(ScanMatcherTest, RecoversAKnownOffset) {
  const MultiResolutionMap map =
      MapFrom({core::Pose2(-1, 0, 0), core::Pose2(0.5, 0.5, 0.3)}, world_);
  const core::Pose2 truth(0.2, -0.3, 0.1);
  ScanMatcherOptions options;
  options.prior_sigma_xy_m = 0;  // no prior: the scan alone must find it
  const std::vector<Eigen::Vector2d> points = Points(ScanFrom(truth, world_));
  const MatchResult m = MatchScan(map, points, core::Pose2(0.32, -0.22, 0.14), {}, options);
  EXPECT_FALSE(m.rejected);
  EXPECT_NEAR(m.pose.x_m, truth.x_m, 0.02);
  EXPECT_NEAR(m.pose.y_m, truth.y_m, 0.02);
  EXPECT_NEAR(m.pose.theta_rad, truth.theta_rad, 0.005);
  EXPECT_GT(MeanMapValue(map, points, m.pose), 0.6);
  EXPECT_LT(MeanMapValue(map, points, core::Pose2(0.32, -0.22, 0.14)), 0.3);
}

TEST_F(ScanMatcherTest, TheOdometryPriorHoldsAFeaturelessCorridor) {
  // A long corridor seen without its ends: the scan says nothing about motion along it.
  core::OccupancyGrid corridor(core::GridGeometry(0.05, 400, 60, core::Pose2(-10, -1.5, 0)));
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 400; ++x)
      corridor.SetState({x, y},
                        y == 0 || y == 59 ? core::CellState::kOccupied : core::CellState::kFree);
  const MultiResolutionMap map = MapFrom({core::Pose2(0, 0, 0)}, corridor, 19.5);
  core::LaserScan scan = ScanFrom(core::Pose2(0.3, 0, 0), corridor);
  for (float& r : scan.ranges_m) r = std::min(r, 6.0f);  // the ends are out of reach
  for (float& r : scan.ranges_m)
    if (r >= 6.0f) r = INFINITY;
  const core::Pose2 prediction(0.3, 0.04, 0.0);  // odometry is right along, 4 cm off across
  const MatchResult m = MatchScan(map, Points(scan), prediction, core::Pose2(0.02, 0, 0), {});
  EXPECT_FALSE(m.rejected) << m.pose.ToString();
  EXPECT_NEAR(m.pose.x_m, 0.3, 0.02);   // along the corridor: the prior's value
  EXPECT_NEAR(m.pose.y_m, 0.0, 0.015);  // across: the walls correct the odometry
  // Without the prior nothing holds the pose along the corridor.
  ScanMatcherOptions no_prior;
  no_prior.prior_sigma_xy_m = 0;
  // The descent alone: a heading search may start it from a slightly turned heading, from
  // which it slides less far.
  no_prior.heading_search_base_rad = no_prior.heading_search_per_rad = 0;
  const MatchResult slid =
      MatchScan(map, Points(scan), prediction, core::Pose2(0.02, 0, 0), no_prior);
  EXPECT_TRUE(slid.rejected || std::abs(slid.pose.x_m - 0.3) > 0.05) << slid.pose.ToString();
}

TEST_F(ScanMatcherTest, TheHeadingSearchCatchesAFastTurnThatOdometryLags) {
  const MultiResolutionMap map =
      MapFrom({core::Pose2(-1, 0, 0), core::Pose2(0.5, 0.5, 0.3)}, world_);
  // The vehicle turned 0.45 rad since the last scan; its odometry, a period old, says 0.3.
  const core::Pose2 truth(0.2, -0.3, 0.45);
  const core::Pose2 prediction(0.2, -0.3, 0.3), odometry(0, 0, 0.3);
  const std::vector<Eigen::Vector2d> points = Points(ScanFrom(truth, world_));
  const MatchResult m = MatchScan(map, points, prediction, odometry, {});
  EXPECT_FALSE(m.rejected);
  EXPECT_NEAR(m.pose.theta_rad, truth.theta_rad, 0.002);
  EXPECT_NEAR(m.pose.x_m, truth.x_m, 0.02);
  EXPECT_NEAR(m.pose.y_m, truth.y_m, 0.02);
  // This room is kind to Gauss-Newton, whose coarse levels bridge 0.15 rad here too. With
  // one step on the finest level only, the search alone brings the heading into reach.
  ScanMatcherOptions one_step;
  one_step.coarse_iterations = 0;
  one_step.fine_iterations = 1;
  EXPECT_NEAR(MatchScan(map, points, prediction, odometry, one_step).pose.theta_rad,
              truth.theta_rad, 0.02);
  one_step.heading_search_base_rad = one_step.heading_search_per_rad = 0;
  const MatchResult stuck = MatchScan(map, points, prediction, odometry, one_step);
  EXPECT_GT(std::abs(stuck.pose.theta_rad - truth.theta_rad), 0.1) << stuck.pose.ToString();
}

TEST_F(ScanMatcherTest, AFarFetchedMatchFallsBackToThePrediction) {
  const MultiResolutionMap map = MapFrom({core::Pose2(0, 0, 0)}, world_);
  ScanMatcherOptions options;
  options.max_correction_m = 0.01;  // any real correction counts as too far here
  options.prior_sigma_xy_m = 0;
  const core::Pose2 prediction(0.1, 0.1, 0.05);
  const MatchResult m =
      MatchScan(map, Points(ScanFrom(core::Pose2(), world_)), prediction, {}, options);
  EXPECT_TRUE(m.rejected);
  EXPECT_EQ(m.pose.x_m, prediction.x_m);
}

TEST_F(ScanMatcherTest, NoPointsLeavesThePrediction) {
  const MultiResolutionMap map = MapFrom({core::Pose2()}, world_);
  const MatchResult m = MatchScan(map, {}, core::Pose2(1, 2, 3), {}, {});
  EXPECT_EQ(m.pose.x_m, 1.0);
  EXPECT_EQ(m.points, 0);
}

// A vehicle standing still (no odometry motion) is not matched again: its pose stays where the
// last match put it, even when its scan hints otherwise. With the rest thresholds at 0 every
// scan is matched, and the same scan moves the pose.
TEST_F(ScanMatcherTest, ALocalMapperDoesNotMatchTheScansOfAVehicleStandingStill) {
  const core::Pose2 start(0, 0, 0), ahead(0.03, 0, 0);
  LocalMapperOptions options;
  options.map.size_m = 12;
  LocalMapper still(options, start);
  still.AddScan(ScanFrom(start, world_), core::Pose2(), core::Pose2());
  const ScanUpdate rest = still.AddScan(ScanFrom(ahead, world_), core::Pose2(), core::Pose2());
  EXPECT_TRUE(rest.at_rest);
  EXPECT_FALSE(rest.matched);
  EXPECT_EQ(rest.pose.x_m, 0.0);
  // Any motion above the thresholds is matched again.
  const ScanUpdate moving =
      still.AddScan(ScanFrom(core::Pose2(0.05, 0, 0), world_), core::Pose2(0.02, 0, 0), {});
  EXPECT_TRUE(moving.matched);
  EXPECT_FALSE(moving.at_rest);
  EXPECT_NEAR(moving.pose.x_m, 0.05, 0.01);

  options.rest_max_translation_m = options.rest_max_rotation_rad = 0;
  LocalMapper every(options, start);
  every.AddScan(ScanFrom(start, world_), core::Pose2(), core::Pose2());
  const ScanUpdate matched = every.AddScan(ScanFrom(ahead, world_), core::Pose2(), core::Pose2());
  EXPECT_TRUE(matched.matched);
  EXPECT_FALSE(matched.at_rest);
  EXPECT_GT(matched.pose.x_m, 0.015);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
