// The agent node in memory: the simulated room's scans and odometry in as LCM messages,
// POSE_/DIVERGENCE_/TEMPMAP_/MAP_REQUEST/STATUS_ out through a recording publisher.
#include "vehicle_agent/node/agent_node.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fleetmap/tempmap_ack_t.hpp"
#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

std::unique_ptr<AgentNode> MakeNode(const AgentNodeOptions& options, RecordingPublisher* out,
                                    std::optional<core::OccupancyGrid> map, double now_s = 0.0) {
  auto node = AgentNode::Create(options, out, nullptr, std::move(map), now_s);
  EXPECT_TRUE(node.ok()) << node.status().ToString();
  return std::move(node).value();
}

TEST(AgentNodeTest, LocalizesAndPublishesPoseAndDivergenceOnTheStaticMap) {
  const sim::World world = testing::RoomWorld();
  RecordingPublisher out;
  auto node = MakeNode(testing::RoomOptions(world), &out, world.static_map());
  const auto truth = testing::DriveNode(world, *node, 6.0);

  // At start it asks the aggregator for what was merged since its version 0.
  const auto requests = out.Decoded<fleetmap::map_request_t>("MAP_REQUEST");
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].vehicle_id, "v1");
  EXPECT_EQ(requests[0].have_version, 0);
  for (const testing::SentMessage& m : out.sent) EXPECT_EQ(m.link, Link::kUplink) << m.channel;

  const auto poses = out.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1");
  ASSERT_EQ(poses.size(), truth.size());  // one per scan
  int close = 0;
  for (const auto& p : poses) {
    EXPECT_EQ(p.vehicle_id, "v1");
    EXPECT_EQ(p.map_version, 0);
    const core::Pose2& t = truth.at(p.utime);
    close += std::hypot(p.pose.x_m - t.x_m, p.pose.y_m - t.y_m) < 0.05;
  }
  EXPECT_GT(close, 0.9 * poses.size());
  const auto divergence = out.Decoded<fleetmap::divergence_t>("DIVERGENCE_v1");
  ASSERT_EQ(divergence.size(), poses.size());
  EXPECT_EQ(divergence.back().vehicle_id, "v1");
  EXPECT_EQ(divergence.back().state, fleetmap::divergence_t::FREE);  // nothing changed
  EXPECT_EQ(out.Count("TEMPMAP_v1"), 0u);

  // A heartbeat per second of node time, with the counters.
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_agent_v1");
  ASSERT_GE(status.size(), 6u);
  EXPECT_LE(status.size(), 7u);
  EXPECT_EQ(status.back().process, "agent_v1");
  EXPECT_EQ(status.back().state, "running");
  EXPECT_EQ(status.back().map_version, 0);
  EXPECT_EQ(node->state(), "running");
  EXPECT_EQ(testing::Counter(*node, "scans"), static_cast<int64_t>(poses.size()));
  EXPECT_EQ(testing::Counter(*node, "scans_skipped"), 0);
  EXPECT_EQ(testing::Counter(*node, "malformed_messages"), 0);
}

TEST(AgentNodeTest, APalletAppearingIsSentAsTilesThatAssembleIntoItsTemporaryMap) {
  const sim::World world = testing::RoomWorld(testing::kPallet);
  RecordingPublisher out;
  auto node = MakeNode(testing::RoomOptions(world), &out, world.static_map());
  bool saw_building = false;
  testing::DriveNode(world, *node, 16.0,
                     [&](double) { saw_building |= node->state() == "building"; });
  node->Shutdown(16.0);
  EXPECT_TRUE(saw_building);
  const auto tiles = out.Decoded<fleetmap::tempmap_tile_t>("TEMPMAP_v1");
  ASSERT_FALSE(tiles.empty());
  core::TempMapAssembler assembler;
  std::map<int32_t, core::TempMap> by_sequence;  // unacknowledged maps are sent again
  for (const auto& m : tiles) {
    auto tile = lcmtypes::FromMessage(m);
    ASSERT_TRUE(tile.ok()) << tile.status().ToString();
    auto map = assembler.Add(*tile);
    ASSERT_TRUE(map.ok()) << map.status().ToString();
    if (*map) by_sequence.emplace((*map)->sequence, **map);
  }
  std::vector<core::TempMap> maps;
  for (auto& [sequence, map] : by_sequence) maps.push_back(std::move(map));
  ASSERT_FALSE(maps.empty());
  EXPECT_EQ(maps[0].vehicle_id, "v1");
  EXPECT_EQ(maps[0].sequence, 1);
  // The pallet's face towards the vehicle (y = 3.8 m) is in a map placed by its anchor.
  int hits = 0;
  for (const core::TempMap& m : maps) {
    const core::GridGeometry placed = m.PlacedGeometry();
    for (double x = 5.1; x <= 5.9; x += 0.05) {
      const core::CellIndex c = placed.WorldToCell({x, 3.825});
      hits += placed.Contains(c) && m.grid.state(c) == core::CellState::kOccupied;
    }
  }
  EXPECT_GT(hits, 8);
  const auto divergence = out.Decoded<fleetmap::divergence_t>("DIVERGENCE_v1");
  bool building_with_seq = false;
  for (const auto& d : divergence)
    building_with_seq |= d.state == fleetmap::divergence_t::BUILDING && d.tempmap_seq == 1;
  EXPECT_TRUE(building_with_seq);
  EXPECT_EQ(testing::Counter(*node, "tempmaps_closed"), static_cast<int64_t>(maps.size()));
  EXPECT_GT(testing::Counter(*node, "tiles_resent"), 0);  // nobody acknowledged them
  EXPECT_EQ(testing::Counter(*node, "tempmaps_pending"), static_cast<int64_t>(maps.size()));
}

TEST(AgentNodeTest, WithExternalLocalizationTheFirstExternalPoseStartsTheFilter) {
  const sim::World world = testing::RoomWorld();
  AgentNodeOptions options = testing::RoomOptions(world);
  options.use_external_pose = true;
  options.initial_pose = InitialPoseSource::kFirstExternal;
  options.pipeline.localizer.initial_pose_in_map = core::Pose2(9.0, 5.0, 3.0);  // not used
  RecordingPublisher out;
  auto node = MakeNode(options, &out, world.static_map());
  bool subscribed = false;
  for (const Subscription& s : node->Subscriptions()) subscribed |= s.channel == "EXTPOSE_v1";
  EXPECT_TRUE(subscribed);
  testing::DriveNode(world, *node, 1.0);
  EXPECT_EQ(node->state(), "waiting_for_pose");
  EXPECT_GT(testing::Counter(*node, "scans_waiting_for_pose"), 20);
  EXPECT_EQ(out.Count("POSE_v1"), 0u);
  // The vehicle's own localization reports where it is.
  core::PoseEstimate external;
  external.stamp_s = 1.0;
  external.pose_in_map = world.VehicleStateAt(0, 1.0).pose;
  testing::FeedMessage(*node, Link::kSensor, "EXTPOSE_v1", lcmtypes::ToMessage(external, "v1"),
                       1.0);
  const size_t mark = out.sent.size();
  const auto truth = testing::DriveNode(world, *node, 4.0, {}, 1.0);
  EXPECT_EQ(node->state(), "running");
  const auto poses = out.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1", mark);
  ASSERT_GT(poses.size(), 50u);
  const core::Pose2& t = truth.at(poses.back().utime);
  EXPECT_LT(std::hypot(poses.back().pose.x_m - t.x_m, poses.back().pose.y_m - t.y_m), 0.05);
  EXPECT_EQ(testing::Counter(*node, "external_poses"), 1);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
