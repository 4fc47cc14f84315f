#include "vehicle_agent/localization/pose_hypotheses.h"

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

// Follows `start` for `scans` steps of the vehicle driving 0.1 m and turning a little; the
// scans are seen in `world` (the map unless given: a building that changed).
PoseHypotheses Follow(const core::OccupancyGrid& map, core::Pose2& truth,
                      const std::vector<core::Pose2>& start, int scans,
                      const std::vector<double>& head_start = {},
                      const core::OccupancyGrid* world = nullptr) {
  if (!world) world = &map;
  LikelihoodField field({});
  field.SetMap(map);
  PoseHypotheses h({});
  std::vector<PoseHypothesis> seeds;
  for (size_t i = 0; i < start.size(); ++i)
    seeds.push_back({start[i], i < head_start.size() ? head_start[i] : 0.0});
  std::vector<Eigen::Vector2f> points = PointsSeenFrom(*world, truth);
  h.Start(seeds, {map, field, points, core::Pose2()});
  const core::Pose2 step(0.1, 0.0, 0.02);
  for (int i = 0; i < scans; ++i) {
    truth = truth * step;
    points = PointsSeenFrom(*world, truth);
    h.Update(step, {map, field, points, core::Pose2()});
  }
  return h;
}

// A box breaks the room's symmetry: the true pose, started 8 cm and 2 degrees off, is fitted
// and leads its twin until it is taken, once the vehicle drove 2 m (the twin's beams that end
// on the box's empty twin place count as an object the map lacks: less than a fit, more than
// nothing).
TEST(PoseHypothesesTest, TheTruePoseLeadsItsTwinAndIsTaken) {
  core::OccupancyGrid map = test_grids::Room(2);
  test_grids::AddBox(map, 7.0, 4.0, 8.5, 5.0);
  core::Pose2 truth(3.0, 2.0, 0.5);
  const core::Pose2 off(truth.x_m + 0.06, truth.y_m - 0.05, truth.theta_rad + 0.035);
  const PoseHypotheses h = Follow(map, truth, {Twin(truth), off}, 20);
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

// A pose found later enters decide_margin behind the best: it is followed, and taken only if
// it proves better; here it is the twin, and the true pose keeps the lead.
TEST(PoseHypothesesTest, APoseFoundLaterMustProveItselfBetter) {
  const core::OccupancyGrid map = test_grids::Room(2);
  core::Pose2 truth(3.0, 2.0, 0.5);
  LikelihoodField field({});
  field.SetMap(map);
  PoseHypotheses h({});
  std::vector<Eigen::Vector2f> points = PointsSeenFrom(map, truth);
  h.Start({{truth, 0.0}}, {map, field, points, core::Pose2()});
  h.Add({{Twin(truth), 0.0}}, {map, field, points, core::Pose2()});
  ASSERT_EQ(h.all().size(), 2u);
  EXPECT_LT(Distance(h.best().base_in_map, truth), 0.05);
  EXPECT_NEAR(h.all()[0].evidence - h.all()[1].evidence, PoseHypothesesOptions{}.decide_margin,
              0.5);
}

// Beams that end on a box the map lacks, short of the walls in mapped free space, are the
// building's change: the true pose, started beside a pose 0.6 m off, keeps the lead though
// the box hides a quarter of the room, and the wrong pose is dropped.
TEST(PoseHypothesesTest, AnObjectTheMapLacksDoesNotCountAgainstTheTruePose) {
  core::OccupancyGrid map = test_grids::Room(2);
  test_grids::AddBox(map, 7.0, 4.0, 8.5, 5.0);
  core::OccupancyGrid world = map;
  test_grids::AddBox(world, 4.0, 1.0, 4.4, 3.5);  // in front of the vehicle, not in the map
  core::Pose2 truth(3.0, 2.0, 0.1);
  const core::Pose2 off(truth.x_m - 0.6, truth.y_m + 0.3, truth.theta_rad);
  const PoseHypotheses h = Follow(map, truth, {off, truth}, 4, {}, &world);
  EXPECT_LT(Distance(h.best().base_in_map, truth), 0.05);
}

TEST(PoseHypothesesTest, ValidateNamesBadOptions) {
  EXPECT_TRUE(PoseHypothesesOptions{}.Validate().ok());
  PoseHypothesesOptions o;
  o.drop_margin = o.decide_margin / 2;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.fit_min_step_m = 0;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.short_beam_as_m = 0;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.fit_prior_sigma_m = 0;
  EXPECT_FALSE(o.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
