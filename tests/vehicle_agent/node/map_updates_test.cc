// The map in use: versions handed to the pipeline as their tiles complete them, refused tiles
// logged once, and the catch-up request after the aggregator's versions went back.
#include "vehicle_agent/node/map_updates.h"

#include <gtest/gtest.h>

#include "tests/sim/sim_test_util.h"
#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

std::vector<core::KeyframeTile> Keyframe(const core::OccupancyGrid& g, int32_t version) {
  return testing::KeyframeTiles(g, version);
}

class MapUpdatesTest : public ::testing::Test {
 protected:
  MapUpdatesTest()
      : log_([this](LogLevel level, const std::string& line) {
          (level == LogLevel::kWarning ? warnings_ : infos_).push_back(line);
        }),
        maps_(MapFollowerOptions{}, &log_, &counters_),
        pipeline_(AgentPipelineOptions{}) {}

  std::vector<std::string> infos_, warnings_;
  CauseLog log_;
  AgentNodeCounters counters_;
  MapUpdates maps_;
  AgentPipeline pipeline_;
};

TEST_F(MapUpdatesTest, AVersionGoesToThePipelineOnceItsTilesAreInAndOnlyTheFirstStartsIt) {
  EXPECT_FALSE(maps_.Apply(pipeline_));  // nothing yet
  EXPECT_FALSE(maps_.in_use());
  EXPECT_EQ(maps_.version_in_use(), -1);
  const auto key = Keyframe(sim::testing::Room(), 4);
  ASSERT_GT(key.size(), 1u);
  for (size_t i = 0; i + 1 < key.size(); ++i) maps_.OnKeyframeTile(key[i]);
  EXPECT_FALSE(maps_.Apply(pipeline_));  // one tile still missing
  EXPECT_EQ(pipeline_.localizer().map_version(), -1);

  EXPECT_TRUE(infos_.empty());
  maps_.OnKeyframeTile(key.back());
  ASSERT_EQ(infos_.size(), 1u);
  EXPECT_EQ(infos_[0], "map version 4 held (" + std::to_string(key.size()) + " keyframe tiles)");
  EXPECT_TRUE(maps_.Apply(pipeline_));  // the first map
  EXPECT_TRUE(maps_.in_use());
  EXPECT_EQ(maps_.version_in_use(), 4);
  EXPECT_EQ(pipeline_.localizer().map_version(), 4);
  ASSERT_EQ(infos_.size(), 2u);
  EXPECT_EQ(infos_[1], "map version 4 in use");
  EXPECT_FALSE(maps_.Apply(pipeline_));  // handed over once
  EXPECT_EQ(infos_.size(), 2u);

  maps_.OnDeltaTile({4, 0, 0, {}, {}});  // version 5 changed no cell
  EXPECT_FALSE(maps_.Apply(pipeline_));  // a later map: not the first
  EXPECT_EQ(maps_.version_in_use(), 5);
  EXPECT_EQ(pipeline_.localizer().map_version(), 5);
  EXPECT_EQ(maps_.follower().counters().versions_applied, 2);
  EXPECT_TRUE(warnings_.empty());
}

TEST_F(MapUpdatesTest, ASeededMapIsDueAtOnceAndRefusedTilesAreLoggedOncePerCause) {
  ASSERT_TRUE(maps_.Seed(sim::testing::Room(), 0).ok());
  core::OccupancyGrid other(core::GridGeometry(0.1, 100, 60));
  for (int i = 0; i < 3; ++i) maps_.OnKeyframeTile(Keyframe(other, 9)[0]);
  EXPECT_EQ(maps_.follower().counters().wrong_geometry_tiles, 3);
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("MAP_KEYFRAME: tile refused"), std::string::npos) << warnings_[0];
  EXPECT_TRUE(maps_.Apply(pipeline_));
  EXPECT_EQ(maps_.version_in_use(), 0);
  EXPECT_EQ(counters_.map_swaps_failed, 0);
}

TEST_F(MapUpdatesTest, AnAggregatorWhoseVersionsWentBackIsAskedForItsMapAndOursStaysInUse) {
  EXPECT_EQ(maps_.RequestDue(0.0), -1);  // no map: the whole one
  for (const core::KeyframeTile& tile : Keyframe(sim::testing::Room(), 4))
    maps_.OnKeyframeTile(tile);
  ASSERT_TRUE(maps_.Apply(pipeline_));
  maps_.OnRemoteVersion(2, 10.0);
  EXPECT_FALSE(maps_.RequestDue(11.0));  // a heartbeat overtaken by a delta is no restart
  EXPECT_TRUE(warnings_.empty());
  EXPECT_EQ(maps_.RequestDue(12.0), -1);  // two periods behind: the replica is dropped
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("went back below 4"), std::string::npos) << warnings_[0];
  EXPECT_EQ(maps_.follower().counters().resets, 1);
  EXPECT_TRUE(maps_.in_use());
  EXPECT_EQ(maps_.version_in_use(), 4);
  EXPECT_EQ(pipeline_.localizer().map_version(), 4);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
