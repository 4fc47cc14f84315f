#include "vehicle_agent/pose_hypotheses.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/vehicle_agent/test_grids.h"

namespace fleetmap::vehicle_agent {
namespace {

std::vector<Eigen::Vector2f> PointsSeenFrom(const core::OccupancyGrid& map,
                                            const core::Pose2& base_in_map) {
  return test_grids::EndpointsSeenFrom(map, base_in_map, 60);
}

double Distance(const core::Pose2& a, const core::Pose2& b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
}

// The 10 m x 6 m room looks the same turned by half a turn about its middle.
core::Pose2 Twin(const core::Pose2& p) {
  return core::Pose2(10.0 - p.x_m, 6.0 - p.y_m, core::NormalizeAngle(p.theta_rad + M_PI));
}

// Follows `start` for `scans` steps of the vehicle driving 0.1 m and turning a little.
PoseHypotheses Follow(const core::OccupancyGrid& map, core::Pose2& truth,
                      const std::vector<core::Pose2>& start, int scans,
                      const std::vector<double>& head_start = {}) {
  LikelihoodField field({});
  field.SetMap(map);
  PoseHypotheses h({});
  std::vector<PoseHypothesis> seeds;
  for (size_t i = 0; i < start.size(); ++i)
    seeds.push_back({start[i], i < head_start.size() ? head_start[i] : 0.0});
  h.Start(seeds, field, PointsSeenFrom(map, truth));
  const core::Pose2 step(0.1, 0.0, 0.02);
  for (int i = 0; i < scans; ++i) {
    truth = truth * step;
    h.Update(step, field, PointsSeenFrom(map, truth));
  }
  return h;
}

// A box breaks the room's symmetry: the true pose, started 8 cm and 2 degrees off, is fitted
// and leads its twin until it is taken, once the vehicle drove a metre.
TEST(PoseHypothesesTest, TheTruePoseLeadsItsTwinAndIsTaken) {
  core::OccupancyGrid map = test_grids::Room(2);
  test_grids::AddBox(map, 7.0, 4.0, 8.5, 5.0);
  core::Pose2 truth(3.0, 2.0, 0.5);
  const core::Pose2 off(truth.x_m + 0.06, truth.y_m - 0.05, truth.theta_rad + 0.035);
  const PoseHypotheses h = Follow(map, truth, {Twin(truth), off}, 10);
  ASSERT_TRUE(h.active());
  EXPECT_TRUE(h.decided());
  EXPECT_LT(Distance(h.best().base_in_map, truth), 0.05);
  EXPECT_LT(std::abs(core::NormalizeAngle(h.best().base_in_map.theta_rad - truth.theta_rad)), 0.01);
}

// Without the box no scan tells the two apart: both are followed and none is taken; the
// covariance says how far apart they are.
TEST(PoseHypothesesTest, TwinsNoScanTellsApartStayOpen) {
  const core::OccupancyGrid map = test_grids::Room(2);
  core::Pose2 truth(3.0, 2.0, 0.5);
  const PoseHypotheses h = Follow(map, truth, {truth, Twin(truth)}, 10);
  ASSERT_EQ(h.all().size(), 2u);
  EXPECT_FALSE(h.decided());
  EXPECT_NEAR(h.all()[0].evidence, h.all()[1].evidence, 0.5);
  const double apart = Distance(h.all()[0].base_in_map, h.all()[1].base_in_map);
  EXPECT_GT(apart, 2.0);
  const Eigen::Matrix3d c = h.Covariance(Eigen::Vector3d(0.01, 0.01, 0.001));
  EXPECT_NEAR(std::sqrt(c(0, 0) + c(1, 1)), apart / std::sqrt(2.0), 0.05);
}

// Hypotheses that end up at the same pose are one; one left is decided.
// The pose the vehicle held starts ahead: one scan that fits a wrong pose better does not
// make it the best, driving on does.
TEST(PoseHypothesesTest, TheHeldPoseKeepsItsPlaceUntilDrivingSaysOtherwise) {
  core::OccupancyGrid map = test_grids::Room(2);
  test_grids::AddBox(map, 7.0, 4.0, 8.5, 5.0);
  core::Pose2 truth(3.0, 2.0, 0.5);
  const core::Pose2 held(4.5, 2.5, 0.5);  // 1.6 m off: the scans contradict it
  const PoseHypotheses first = Follow(map, truth, {held, truth}, 0, {10.0, 0.0});
  ASSERT_EQ(first.all().size(), 2u);
  EXPECT_LT(Distance(first.best().base_in_map, held), 0.5);  // a fit moves it a little
  EXPECT_FALSE(first.decided());
  const PoseHypotheses later = Follow(map, truth, {held, truth}, 30, {4.0, 0.0});
  EXPECT_LT(Distance(later.best().base_in_map, truth), 0.05);
  EXPECT_TRUE(later.decided());
}

TEST(PoseHypothesesTest, HypothesesThatMeetAreOne) {
  core::OccupancyGrid map = test_grids::Room(2);
  test_grids::AddBox(map, 7.0, 4.0, 8.5, 5.0);
  core::Pose2 truth(3.0, 2.0, 0.5);
  const core::Pose2 a(truth.x_m + 0.05, truth.y_m, truth.theta_rad);
  const core::Pose2 b(truth.x_m, truth.y_m - 0.05, truth.theta_rad + 0.02);
  const PoseHypotheses h = Follow(map, truth, {a, b}, 1);
  EXPECT_EQ(h.all().size(), 1u);
  EXPECT_TRUE(h.decided());
}

TEST(PoseHypothesesTest, ValidateNamesBadOptions) {
  EXPECT_TRUE(PoseHypothesesOptions{}.Validate().ok());
  PoseHypothesesOptions o;
  o.drop_margin = o.decide_margin / 2;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.fit_min_step_m = 0;
  EXPECT_FALSE(o.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
