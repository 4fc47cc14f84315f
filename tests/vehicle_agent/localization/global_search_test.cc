#include "vehicle_agent/localization/global_search.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/vehicle_agent/test_grids.h"

namespace fleetmap::vehicle_agent {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The 10 m x 6 m room with two boxes that make every pose unique.
core::OccupancyGrid Room(core::Pose2 origin = {}) {
  core::OccupancyGrid grid = test_grids::Room(2, origin);
  test_grids::AddBox(grid, 7.0, 4.0, 8.5, 5.0);
  test_grids::AddBox(grid, 2.0, 1.0, 2.6, 2.2);
  return grid;
}

std::vector<Eigen::Vector2f> PointsSeenFrom(const core::OccupancyGrid& map,
                                            const core::Pose2& base_in_map) {
  return test_grids::EndpointsSeenFrom(map, base_in_map, 360);
}

void ExpectNear(const core::Pose2& found, const core::Pose2& truth) {
  const core::Pose2 d = core::Between(truth, found);
  EXPECT_LT(std::hypot(d.x_m, d.y_m), 0.12) << found.x_m << " " << found.y_m;
  EXPECT_LT(std::abs(d.theta_rad), 2 * kDeg) << found.theta_rad;
}

TEST(GlobalSearchTest, FindsTheVehicleAnywhereInTheRoom) {
  const core::OccupancyGrid map = Room();
  const GlobalSearch search(map, {});
  for (const core::Pose2& truth : {core::Pose2(1.3, 4.4, 0.3), core::Pose2(5.0, 3.0, -2.0),
                                   core::Pose2(8.8, 1.2, 3.0), core::Pose2(4.1, 5.2, 1.57)}) {
    const auto found = search.Search(PointsSeenFrom(map, truth));
    ASSERT_FALSE(found.empty());
    ExpectNear(found.front().base_in_map, truth);
    EXPECT_GT(found.front().score, 0.8);
  }
}

TEST(GlobalSearchTest, AMapTurnedInItsGridIsSearchedInTheMapFrame) {
  const core::OccupancyGrid map = Room(core::Pose2(-3.0, 2.0, 0.4));
  const GlobalSearch search(map, {});
  const core::Pose2 truth = map.geometry().origin() * core::Pose2(6.0, 2.5, 0.8);
  const auto found = search.Search(PointsSeenFrom(map, truth));
  ASSERT_FALSE(found.empty());
  ExpectNear(found.front().base_in_map, truth);
}

// Branch and bound drops regions by their bound only: it finds the score the exhaustive
// search (one level: every position and heading scored) finds.
TEST(GlobalSearchTest, BranchAndBoundFindsWhatTheExhaustiveSearchFinds) {
  const core::OccupancyGrid map = Room();
  GlobalSearchOptions exhaustive;
  exhaustive.levels = 1;
  exhaustive.resolution_m = 0.2;
  GlobalSearchOptions fast = exhaustive;
  fast.levels = 6;
  const auto points = PointsSeenFrom(map, core::Pose2(3.3, 3.7, 2.2));
  const auto a = GlobalSearch(map, exhaustive).Search(points);
  const auto b = GlobalSearch(map, fast).Search(points);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  EXPECT_DOUBLE_EQ(a.front().score, b.front().score);
  ExpectNear(b.front().base_in_map, a.front().base_in_map);
}

// An empty rectangular room looks the same turned by half a turn: both poses come back,
// distinct, with the same score; one scan cannot tell them apart.
TEST(GlobalSearchTest, ASymmetricRoomGivesEveryPoseThatFits) {
  const core::OccupancyGrid map = test_grids::Room(2);
  const core::Pose2 truth(3.0, 2.0, 0.5);
  const auto found = GlobalSearch(map, {}).Search(PointsSeenFrom(map, truth));
  ASSERT_GE(found.size(), 2u);
  const core::Pose2 twin(10.0 - 3.0, 6.0 - 2.0, core::NormalizeAngle(0.5 + M_PI));
  int near_truth = 0, near_twin = 0;
  for (size_t i = 0; i < 2; ++i) {
    const core::Pose2 d1 = core::Between(truth, found[i].base_in_map);
    const core::Pose2 d2 = core::Between(twin, found[i].base_in_map);
    near_truth += std::hypot(d1.x_m, d1.y_m) < 0.15;
    near_twin += std::hypot(d2.x_m, d2.y_m) < 0.15;
  }
  EXPECT_EQ(near_truth, 1);
  EXPECT_EQ(near_twin, 1);
  EXPECT_NEAR(found[0].score, found[1].score, 0.05);
}

// Score is the search's own measure at one pose: the best found scores what the truth scores,
// a pose a metre off far less; the localizer compares the two to decide it is lost.
TEST(GlobalSearchTest, ScoresAPoseAsTheSearchDoes) {
  const core::OccupancyGrid map = Room();
  const GlobalSearch search(map, {});
  const core::Pose2 truth(5.0, 3.0, -2.0);
  const auto points = PointsSeenFrom(map, truth);
  const auto found = search.Search(points);
  ASSERT_FALSE(found.empty());
  EXPECT_NEAR(search.Score(points, truth), found.front().score, 0.1);
  EXPECT_GT(search.Score(points, truth), 0.8);
  EXPECT_LT(search.Score(points, core::Pose2(6.0, 3.5, -1.8)), 0.5);
  EXPECT_EQ(search.Score({{1.0f, 0.0f}}, truth), 0.0);
}

TEST(GlobalSearchTest, TooFewPointsOrNoFitGiveNothing) {
  const core::OccupancyGrid map = Room();
  const GlobalSearch search(map, {});
  EXPECT_TRUE(search.Search({{1.0f, 0.0f}, {0.0f, 1.0f}}).empty());
  // Points on a circle of 50 m: nothing in the room is like that.
  std::vector<Eigen::Vector2f> far;
  for (int i = 0; i < 100; ++i)
    far.emplace_back(15.0f * std::cos(i * 0.0628f), 15.0f * std::sin(i * 0.0628f));
  EXPECT_TRUE(search.Search(far).empty());
  GlobalSearchOptions bad;
  bad.levels = 0;
  EXPECT_FALSE(bad.Validate().ok());
  EXPECT_TRUE(GlobalSearchOptions{}.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
