#include "vehicle_agent/node/map_follower.h"

#include <gtest/gtest.h>

#include "tests/sim/sim_test_util.h"
#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

std::vector<core::KeyframeTile> Keyframe(const core::OccupancyGrid& g, int32_t version) {
  return testing::KeyframeTiles(g, version);
}

// Without a map it asks once per period, for the whole map, then for the tiles it lacks.
TEST(MapFollowerTest, WithoutAMapAsksOncePerPeriodForWhatItLacks) {
  MapFollower f({});
  EXPECT_EQ(f.RequestDue(10.0), -1);
  EXPECT_TRUE(f.request_tiles().empty()) << "the whole map";
  EXPECT_FALSE(f.RequestDue(10.5));
  EXPECT_EQ(f.RequestDue(11.0), -1);
  const auto key = Keyframe(sim::testing::Room(), 4);
  ASSERT_GE(key.size(), 2u);
  for (size_t i = 0; i + 1 < key.size(); ++i) EXPECT_FALSE(*f.OnKeyframeTile(key[i]));
  EXPECT_EQ(f.RequestDue(12.0), -1) << "one tile still missing";
  EXPECT_EQ(f.request_tiles(), (std::vector<int32_t>{key.back().index}));
  EXPECT_TRUE(*f.OnKeyframeTile(key.back()));
  EXPECT_EQ(f.version(), 4);
  for (double t = 13.0; t < 30.0; t += 0.25) EXPECT_FALSE(f.RequestDue(t));
  EXPECT_EQ(f.counters().requests, 3);
  EXPECT_EQ(f.counters().versions_applied, 1);
}

// Lacking more tiles than a request can list, it asks for the whole map again only after a
// period in which no tile came: while they come, the answer is arriving.
TEST(MapFollowerTest, LackingTooManyToListItWaitsWhileTilesArrive) {
  MapFollowerOptions options;
  options.max_request_tiles = 1;
  MapFollower f(options);
  EXPECT_EQ(f.RequestDue(10.0), -1);
  const auto key = Keyframe(sim::testing::Room(), 4);
  ASSERT_GE(key.size(), 3u);
  for (size_t i = 0; i + 2 < key.size(); ++i) EXPECT_FALSE(*f.OnKeyframeTile(key[i]));
  EXPECT_FALSE(f.RequestDue(11.0)) << "tiles came in the last period";
  EXPECT_EQ(f.RequestDue(12.0), -1) << "none since: two tiles still missing";
  EXPECT_TRUE(f.request_tiles().empty()) << "too many to list: the whole map";
  EXPECT_FALSE(*f.OnKeyframeTile(key[key.size() - 2]));
  EXPECT_EQ(f.RequestDue(13.0), -1) << "one left: listed, whatever came";
  EXPECT_EQ(f.request_tiles(), (std::vector<int32_t>{key.back().index}));
  EXPECT_EQ(f.counters().requests, 3);
}

TEST(MapFollowerTest, SeededAsksOnceToCatchUpThenOnlyOnGapsOrAHeartbeatAhead) {
  MapFollower f({});
  ASSERT_TRUE(f.Seed(sim::testing::Room(), 0).ok());
  EXPECT_EQ(f.RequestDue(0.0), 0);
  for (double t = 0.5; t < 5.0; t += 0.5) EXPECT_FALSE(f.RequestDue(t));
  f.OnRemoteVersion(0, 5.0);
  EXPECT_FALSE(f.RequestDue(7.0));  // the aggregator is where we are
  f.OnRemoteVersion(2, 7.0);
  EXPECT_FALSE(f.RequestDue(7.5));  // the delta may be on its way
  EXPECT_EQ(f.RequestDue(8.0), 0);
  EXPECT_FALSE(f.RequestDue(8.5));
  EXPECT_EQ(f.RequestDue(9.0), 0);  // still behind: again, once per period
}

TEST(MapFollowerTest, RefusesAKeyframeOfAnotherGeometryAndCountsOldNews) {
  MapFollower f({});
  ASSERT_TRUE(f.Seed(sim::testing::Room(), 3).ok());
  core::OccupancyGrid other(core::GridGeometry(0.1, 100, 60));
  const auto tile = f.OnKeyframeTile(Keyframe(other, 9)[0]);
  EXPECT_FALSE(tile.ok());
  EXPECT_EQ(tile.status().code(), core::StatusCode::kFailedPrecondition);
  EXPECT_EQ(f.counters().wrong_geometry_tiles, 1);
  EXPECT_FALSE(*f.OnKeyframeTile(Keyframe(sim::testing::Room(), 2)[0]));
  EXPECT_FALSE(*f.OnDeltaTile({1, 0, 0, {}, {}}));
  EXPECT_EQ(f.counters().stale_tiles, 2);
  EXPECT_EQ(f.version(), 3);
  EXPECT_FALSE((MapFollowerOptions{2, 1.0, 16}.Validate().ok()));
  EXPECT_FALSE((MapFollowerOptions{64, 0.0, 16}.Validate().ok()));
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
