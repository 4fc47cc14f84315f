// Telling when the vehicle is lost: which end points a map explains, and when a search of the
// whole map is due.
#include "vehicle_agent/localization/lost_watch.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/vehicle_agent/test_grids.h"

namespace fleetmap::vehicle_agent {
namespace {

TEST(ExplainedShareTest, EndPointsNearAnObstacleOrShortInFreeSpaceAreExplained) {
  core::OccupancyGrid map = test_grids::Room(2);
  test_grids::AddBox(map, 5.0, 0.0, 5.2, 4.0);  // an inner wall from the bottom to y = 4
  for (int y = 2; y < 118; ++y)                 // unknown space beyond x = 8
    for (int x = 160; x < 198; ++x) map.SetState({x, y}, core::CellState::kUnknown);
  LikelihoodField field({});
  field.SetMap(map);
  const core::Pose2 base(1.0, 2.0, 0.0);
  const std::vector<Eigen::Vector2f> endpoints = {
      {3.9f, 0.0f},  // (4.9, 2): 0.1 m before the inner wall
      {3.0f, 0.0f},  // (4, 2): short of it, in free space
      {6.0f, 0.0f},  // (7, 2): through the inner wall, 1.8 m past it
      {8.0f, 3.0f},  // (9, 5): through it into unknown space, 0.9 m from the outer walls
  };
  EXPECT_DOUBLE_EQ(ExplainedShare(map, field, endpoints, base, {}, 0.3), 0.5);
  EXPECT_DOUBLE_EQ(ExplainedShare(map, field, endpoints, base, {}, 1.2), 0.75);
  // The same end points seen from a pose 3 m further on: all of them beyond the inner wall.
  EXPECT_LT(ExplainedShare(map, field, endpoints, core::Pose2(4.5, 2.0, 0.0), {}, 0.3), 0.5);
  EXPECT_TRUE(std::isnan(ExplainedShare(map, field, {}, base, {}, 0.3)));
}

TEST(LostWatchTest, ScansUnexplainedForAWhileMakeASearchDueAndAnExplainedOneStartsAgain) {
  LostWatch watch(2.0, 0.8, 30.0);
  EXPECT_FALSE(watch.SearchDue(std::nan(""), 0.0));  // nothing to judge
  EXPECT_FALSE(watch.SearchDue(0.5, 10.0));          // unexplained from here
  EXPECT_FALSE(watch.SearchDue(0.5, 11.9));
  EXPECT_FALSE(watch.SearchDue(0.9, 11.95));  // explained: the clock starts again
  EXPECT_FALSE(watch.SearchDue(0.5, 12.0));
  EXPECT_FALSE(watch.SearchDue(0.5, 13.9));
  EXPECT_TRUE(watch.SearchDue(0.5, 14.0));
  EXPECT_FALSE(watch.lost());  // due is not lost: the search decides
}

TEST(LostWatchTest, SearchesThatFindNothingBetterComeLessOftenUpToTheLongestWait) {
  LostWatch watch(2.0, 0.8, 10.0);
  ASSERT_FALSE(watch.SearchDue(0.1, 0.0));
  ASSERT_TRUE(watch.SearchDue(0.1, 2.0));
  double now = 2.0;
  for (double wait : {4.0, 8.0, 10.0, 10.0}) {
    watch.NothingBetter(now);
    EXPECT_FALSE(watch.SearchDue(0.1, now + wait - 0.01)) << wait;
    EXPECT_TRUE(watch.SearchDue(0.1, now + wait)) << wait;
    now += wait;
  }
}

TEST(LostWatchTest, FoundElsewhereItIsLostUntilAScanIsExplained) {
  LostWatch watch(2.0, 0.8, 30.0);
  ASSERT_FALSE(watch.SearchDue(0.1, 0.0));
  ASSERT_TRUE(watch.SearchDue(0.1, 2.0));
  watch.FoundElsewhere();
  watch.Restart();  // the particles restart around what the search found
  EXPECT_TRUE(watch.lost());
  EXPECT_FALSE(watch.SearchDue(0.1, 2.5));  // judged afresh from the restart
  EXPECT_FALSE(watch.SearchDue(0.1, 4.4));
  EXPECT_TRUE(watch.SearchDue(0.1, 4.5));
  EXPECT_TRUE(watch.lost());
  EXPECT_FALSE(watch.SearchDue(0.85, 5.0));
  EXPECT_FALSE(watch.lost());
}

TEST(LostWatchTest, WithoutAWaitItIsNeverLost) {
  LostWatch watch(0.0, 0.8, 30.0);
  for (double t = 0.0; t < 100.0; t += 1.0) EXPECT_FALSE(watch.SearchDue(0.0, t));
  EXPECT_FALSE(watch.lost());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
