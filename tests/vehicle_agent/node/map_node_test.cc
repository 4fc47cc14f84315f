// The map catch-up protocol from the vehicle's side: keyframes, deltas, version gaps and the
// aggregator's heartbeat, with tiles made by aggregator-independent code (core/codec/tile_delta.h).
#include <gtest/gtest.h>

#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

core::OccupancyGrid WithBox(core::OccupancyGrid grid, int x0, int y0) {
  for (int y = y0; y < y0 + 10; ++y)
    for (int x = x0; x < x0 + 10; ++x) grid.SetState({x, y}, core::CellState::kOccupied);
  return grid;
}

template <typename T>
void FeedAll(AgentNode& node, const std::string& channel, const std::vector<T>& messages,
             double now_s) {
  for (const T& m : messages) testing::FeedMessage(node, Link::kDownlink, channel, m, now_s);
}

std::vector<int32_t> PoseVersions(const RecordingPublisher& out, size_t from) {
  std::vector<int32_t> versions;
  for (const auto& p : out.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1", from))
    versions.push_back(p.map_version);
  return versions;
}

TEST(MapNodeTest, WithoutAMapItAsksEverySecondThenLocalizesOnTheKeyframe) {
  const sim::World world = testing::RoomWorld();
  AgentNodeOptions options = testing::RoomOptions(world);
  options.pipeline.localizer.initial_pose_in_map = world.VehicleStateAt(0, 2.5).pose;
  RecordingPublisher out;
  auto node = AgentNode::Create(options, &out, nullptr, std::nullopt, 0.0).value();
  EXPECT_EQ(node->state(), "waiting_for_map");
  testing::DriveNode(world, *node, 2.5);
  // Asked at start, after 1 s and after 2 s (utime is the node's time: no offset here).
  const auto asked = out.Decoded<fleetmap::map_request_t>("MAP_REQUEST");
  ASSERT_EQ(asked.size(), 3u);
  for (const auto& r : asked) EXPECT_EQ(r.have_version, -1);
  EXPECT_NEAR((asked[1].utime - asked[0].utime) * 1e-6, 1.0, 0.05);
  EXPECT_NEAR((asked[2].utime - asked[1].utime) * 1e-6, 1.0, 0.05);
  EXPECT_EQ(node->state(), "waiting_for_map");
  EXPECT_GT(testing::Counter(*node, "scans_waiting_for_map"), 50);
  EXPECT_EQ(out.Count("POSE_v1"), 0u);
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_agent_v1");
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.back().state, "waiting_for_map");
  EXPECT_EQ(status.back().map_version, -1);

  // The aggregator's keyframe of version 3: the node localizes on it.
  const core::OccupancyGrid v3 = world.static_map();
  FeedAll(*node, "MAP_KEYFRAME", testing::KeyframeMessages(v3, 3), 2.5);
  size_t mark = out.sent.size();
  testing::DriveNode(world, *node, 4.0, {}, 2.5);
  EXPECT_EQ(node->state(), "running");
  const std::vector<int32_t> versions = PoseVersions(out, mark);
  ASSERT_GT(versions.size(), 30u);
  for (int32_t v : versions) EXPECT_EQ(v, 3);
  EXPECT_EQ(out.Count("MAP_REQUEST", mark), 0u);  // nothing missing

  // A delta of a version after one we missed: ask with the version we hold.
  const core::OccupancyGrid v4 = WithBox(v3, 20, 100), v5 = WithBox(v4, 150, 100);
  FeedAll(*node, "MAP_DELTA", testing::DeltaMessages(v4, v5, 4), 4.0);
  node->Tick(4.0);
  const auto requests = out.Decoded<fleetmap::map_request_t>("MAP_REQUEST", mark);
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].have_version, 3);
  EXPECT_EQ(node->map_version(), 3);
  // The missing delta arrives: both versions apply, and poses carry the newest.
  FeedAll(*node, "MAP_DELTA", testing::DeltaMessages(v3, v4, 3), 4.1);
  mark = out.sent.size();
  testing::DriveNode(world, *node, 5.0, {}, 4.1);
  EXPECT_EQ(node->map_version(), 5);
  for (int32_t v : PoseVersions(out, mark)) EXPECT_EQ(v, 5);
  EXPECT_EQ(testing::Counter(*node, "map_versions_applied"), 3);
  EXPECT_EQ(testing::Counter(*node, "keyframe_requests"), 4);
}

TEST(MapNodeTest, FromTheStaticMapItCatchesUpWithDeltasAndFollowsTheHeartbeat) {
  const sim::World world = testing::RoomWorld();
  RecordingPublisher out;
  auto node = AgentNode::Create(testing::RoomOptions(world), &out, nullptr, world.static_map(), 0.0)
                  .value();
  node->Tick(0.0);
  EXPECT_EQ(node->state(), "running");
  EXPECT_EQ(node->map_version(), 0);
  const core::OccupancyGrid v0 = world.static_map(), v1 = WithBox(v0, 20, 100);
  FeedAll(*node, "MAP_DELTA", testing::DeltaMessages(v0, v1, 0), 0.1);
  // An empty change (a merge that changed nothing) advances the version too.
  FeedAll(*node, "MAP_DELTA", testing::DeltaMessages(v1, v1, 1), 0.1);
  size_t mark = out.sent.size();
  testing::DriveNode(world, *node, 1.0);
  EXPECT_EQ(node->map_version(), 2);
  for (int32_t v : PoseVersions(out, mark)) EXPECT_EQ(v, 2);

  // The aggregator's heartbeat says version 3 and no delta comes: after a request period the
  // node asks from what it holds.
  fleetmap::status_t heartbeat;
  heartbeat.process = "aggregator";
  heartbeat.map_version = 3;
  heartbeat.num_counters = 0;
  mark = out.sent.size();
  testing::FeedMessage(*node, Link::kDownlink, "STATUS_aggregator", heartbeat, 2.0);
  node->Tick(2.5);
  EXPECT_EQ(out.Count("MAP_REQUEST", mark), 0u);
  node->Tick(3.05);
  const auto requests = out.Decoded<fleetmap::map_request_t>("MAP_REQUEST", mark);
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].have_version, 2);
  // A keyframe of version 3 settles it.
  FeedAll(*node, "MAP_KEYFRAME", testing::KeyframeMessages(WithBox(v1, 150, 100), 3), 3.1);
  node->Tick(3.2);
  EXPECT_EQ(node->map_version(), 3);
  mark = out.sent.size();
  for (double t = 3.3; t < 8.0; t += 0.1) node->Tick(t);
  EXPECT_EQ(out.Count("MAP_REQUEST", mark), 0u);
}

TEST(MapNodeTest, AnAggregatorThatRestartedWithoutItsStateIsFollowedAgain) {
  const sim::World world = testing::RoomWorld();
  RecordingPublisher out;
  auto node = AgentNode::Create(testing::RoomOptions(world), &out, nullptr, world.static_map(), 0.0)
                  .value();
  const core::OccupancyGrid v0 = world.static_map(), v1 = WithBox(v0, 20, 100),
                            v2 = WithBox(v1, 150, 100);
  FeedAll(*node, "MAP_DELTA", testing::DeltaMessages(v0, v1, 0), 0.0);
  FeedAll(*node, "MAP_DELTA", testing::DeltaMessages(v1, v2, 1), 0.0);
  node->Tick(0.0);
  ASSERT_EQ(node->map_version(), 2);
  // The aggregator comes back at version 0: one heartbeat behind is not enough ...
  fleetmap::status_t heartbeat;
  heartbeat.process = "aggregator";
  heartbeat.map_version = 0;
  heartbeat.num_counters = 0;
  size_t mark = out.sent.size();
  for (double t = 1.0; t < 2.9; t += 0.5) {
    testing::FeedMessage(*node, Link::kDownlink, "STATUS_aggregator", heartbeat, t);
    node->Tick(t);
  }
  EXPECT_EQ(out.Count("MAP_REQUEST", mark), 0u);
  // ... two request periods are: the node asks for the whole map and keeps localizing.
  testing::FeedMessage(*node, Link::kDownlink, "STATUS_aggregator", heartbeat, 3.0);
  node->Tick(3.0);
  const auto requests = out.Decoded<fleetmap::map_request_t>("MAP_REQUEST", mark);
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].have_version, -1);
  EXPECT_EQ(testing::Counter(*node, "map_resets"), 1);
  EXPECT_EQ(node->state(), "running");
  // Its new history: version 1 is another change than ours was.
  const core::OccupancyGrid other = WithBox(v0, 100, 20);
  FeedAll(*node, "MAP_KEYFRAME", testing::KeyframeMessages(other, 1), 3.5);
  mark = out.sent.size();
  testing::DriveNode(world, *node, 1.0);
  EXPECT_EQ(node->map_version(), 1);
  EXPECT_EQ(node->map().map().state({105, 25}), core::CellState::kOccupied);
  EXPECT_EQ(node->map().map().state({25, 105}), core::CellState::kFree);
  for (int32_t v : PoseVersions(out, mark)) EXPECT_EQ(v, 1);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
