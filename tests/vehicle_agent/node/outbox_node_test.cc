// The agent's temporary maps on the wire: acknowledgements, resends after the backoff, and
// maps that survive a restart of the agent (state folder).
#include <gtest/gtest.h>

#include <set>

#include "core/map/temp_map_file.h"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "tests/support/scratch_folder.h"
#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

// 200 x 150 cells: 4 x 3 = 12 tiles of 64 cells.
core::TempMap HandMadeMap(int32_t sequence) {
  core::TempMap m;
  m.vehicle_id = "v1";
  m.sequence = sequence;
  m.anchor_in_map = core::Pose2(4.0, 2.0, 0.1);
  m.grid = core::OccupancyGrid(core::GridGeometry(0.05, 200, 150, core::Pose2(-5.0, -3.75, 0.0)));
  for (int x = 20; x < 180; ++x) m.grid.SetState({x, 100}, core::CellState::kOccupied);
  m.start_s = 10.0;
  m.end_s = 14.0;
  return m;
}

fleetmap::tempmap_ack_t MakeAck(int32_t sequence, int8_t outcome, std::vector<int16_t> received) {
  fleetmap::tempmap_ack_t a;
  a.vehicle_id = "v1";
  a.tempmap_seq = sequence;
  a.tile_count = 12;
  a.received_tiles = std::move(received);
  a.num_received = static_cast<int32_t>(a.received_tiles.size());
  a.outcome = outcome;
  a.map_version = 3;
  return a;
}

std::set<int32_t> TileIndices(const RecordingPublisher& out, size_t from) {
  std::set<int32_t> indices;
  for (const auto& t : out.Decoded<fleetmap::tempmap_tile_t>("TEMPMAP_v1", from))
    indices.insert(t.tile_index);
  return indices;
}

class OutboxNodeTest : public ::testing::Test {
 protected:
  // A node whose state folder holds unacknowledged maps from a run before.
  std::unique_ptr<AgentNode> NodeWithPendingMap(std::vector<int32_t> sequences = {4}) {
    for (int32_t s : sequences) {
      const std::string file = dir_.File("tempmap_" + std::to_string(s) + ".fmtm");
      EXPECT_TRUE(core::SaveTempMap(HandMadeMap(s), file).ok());
    }
    const sim::World world = testing::RoomWorld();
    auto node = AgentNode::Create(testing::RoomOptions(world, dir_.path()), &out_, nullptr,
                                  world.static_map(), 100.0);
    EXPECT_TRUE(node.ok()) << node.status().ToString();
    return std::move(node).value();
  }
  void SendAck(AgentNode& node, const fleetmap::tempmap_ack_t& ack, double now_s) {
    testing::FeedMessage(node, Link::kDownlink, "TEMPMAP_ACK", ack, now_s);
  }
  fleetmap::testing::ScratchFolder dir_;
  RecordingPublisher out_;
};

TEST_F(OutboxNodeTest, PendingAckResendsOnlyTheMissingTilesAfterTheBackoff) {
  auto node = NodeWithPendingMap();
  node->Tick(100.0);
  EXPECT_EQ(TileIndices(out_, 0).size(), 12u);  // the whole map at once
  for (const auto& t : out_.Decoded<fleetmap::tempmap_tile_t>("TEMPMAP_v1")) {
    EXPECT_EQ(t.tempmap_seq, 4);
    EXPECT_EQ(t.tile_count, 12);
  }
  SendAck(*node, MakeAck(4, fleetmap::tempmap_ack_t::PENDING, {0, 1, 2, 5, 7, 11}), 100.2);
  size_t mark = out_.sent.size();
  node->Tick(100.5);  // before the first resend time (1 s)
  EXPECT_EQ(out_.Count("TEMPMAP_v1", mark), 0u);
  node->Tick(101.1);
  EXPECT_EQ(TileIndices(out_, mark), (std::set<int32_t>{3, 4, 6, 8, 9, 10}));
  EXPECT_EQ(testing::Counter(*node, "tiles_resent"), 6);

  // Merged: the map is done with, nothing more goes out, its file is gone.
  SendAck(*node, MakeAck(4, fleetmap::tempmap_ack_t::MERGED, {}), 101.3);
  mark = out_.sent.size();
  for (double t = 101.5; t < 140.0; t += 0.5) node->Tick(t);
  EXPECT_EQ(out_.Count("TEMPMAP_v1", mark), 0u);
  EXPECT_EQ(testing::Counter(*node, "maps_merged"), 1);
  EXPECT_EQ(testing::Counter(*node, "tempmaps_pending"), 0);
  EXPECT_FALSE(std::filesystem::exists(dir_.File("tempmap_4.fmtm")));
  // A repeated MERGED is not counted twice; another vehicle's ack is not ours.
  SendAck(*node, MakeAck(4, fleetmap::tempmap_ack_t::MERGED, {}), 140.0);
  auto other = MakeAck(4, fleetmap::tempmap_ack_t::MERGED, {});
  other.vehicle_id = "v2";
  SendAck(*node, other, 140.0);
  EXPECT_EQ(testing::Counter(*node, "maps_merged"), 1);
  EXPECT_EQ(testing::Counter(*node, "acks"), 3);
}

// Merged maps are kept (on disk, in retained/). An aggregator that recovered its state at
// version 3 names the recovery in its heartbeat: the map merged into version 4 is sent again,
// whole and once; the one in version 3 is not.
TEST_F(OutboxNodeTest, MergedMapsAreSentAgainOnceWhenTheAggregatorRecovered) {
  auto node = NodeWithPendingMap({4, 5});
  node->Tick(100.0);
  SendAck(*node, MakeAck(4, fleetmap::tempmap_ack_t::MERGED, {}), 100.2);
  auto merged_later = MakeAck(5, fleetmap::tempmap_ack_t::MERGED, {});
  merged_later.map_version = 4;
  SendAck(*node, merged_later, 100.2);
  node->Tick(100.3);
  EXPECT_EQ(testing::Counter(*node, "tempmaps_pending"), 0);
  EXPECT_EQ(testing::Counter(*node, "tempmaps_retained"), 2);
  EXPECT_GT(testing::Counter(*node, "retained_bytes"), 0);

  fleetmap::status_t heartbeat;
  heartbeat.process = "aggregator";
  heartbeat.map_version = 3;
  heartbeat.counter_names = {lcmtypes::kRecoveryIdCounter, lcmtypes::kRecoveredVersionCounter};
  heartbeat.counter_values = {77, 3};
  heartbeat.num_counters = 2;
  size_t mark = out_.sent.size();
  testing::FeedMessage(*node, Link::kDownlink, "STATUS_aggregator", heartbeat, 101.0);
  node->Tick(101.0);
  const auto resent = out_.Decoded<fleetmap::tempmap_tile_t>("TEMPMAP_v1", mark);
  ASSERT_EQ(resent.size(), 12u);
  for (const auto& t : resent) EXPECT_EQ(t.tempmap_seq, 5);
  EXPECT_EQ(testing::Counter(*node, "tempmaps_resent_after_recovery"), 1);
  merged_later.map_version = 5;  // merged again, into the recovered history
  SendAck(*node, merged_later, 101.5);
  mark = out_.sent.size();
  for (double t = 102.0; t < 110.0; t += 0.5) {  // the same recovery, heard again
    testing::FeedMessage(*node, Link::kDownlink, "STATUS_aggregator", heartbeat, t);
    node->Tick(t);
  }
  EXPECT_EQ(out_.Count("TEMPMAP_v1", mark), 0u);
  EXPECT_EQ(testing::Counter(*node, "tempmaps_retained"), 2);
}

TEST_F(OutboxNodeTest, UnacknowledgedTilesAreResentWithGrowingBackoff) {
  auto node = NodeWithPendingMap();
  std::vector<double> sent_at;
  for (double t = 100.0; t < 120.0; t += 0.1) {
    const size_t mark = out_.sent.size();
    node->Tick(t);
    if (out_.Count("TEMPMAP_v1", mark) > 0) sent_at.push_back(t);
  }
  // 100, then after 1, 2, 4, 8 s.
  ASSERT_EQ(sent_at.size(), 5u);
  EXPECT_NEAR(sent_at[1] - sent_at[0], 1.0, 0.11);
  EXPECT_NEAR(sent_at[4] - sent_at[3], 8.0, 0.11);
}

TEST_F(OutboxNodeTest, RejectedAndDuplicateFinishAMapAndAreCounted) {
  auto node = NodeWithPendingMap({4, 5});
  node->Tick(100.0);
  auto rejected = MakeAck(4, fleetmap::tempmap_ack_t::REJECTED, {});
  rejected.reason = "alignment: too few line pairs";
  SendAck(*node, rejected, 100.1);
  SendAck(*node, MakeAck(5, fleetmap::tempmap_ack_t::DUPLICATE, {}), 100.1);
  EXPECT_EQ(testing::Counter(*node, "maps_rejected"), 1);
  EXPECT_EQ(testing::Counter(*node, "maps_duplicate"), 1);
  EXPECT_EQ(testing::Counter(*node, "tempmaps_pending"), 0);
  const size_t mark = out_.sent.size();
  for (double t = 100.5; t < 120.0; t += 0.5) node->Tick(t);
  EXPECT_EQ(out_.Count("TEMPMAP_v1", mark), 0u);
}

TEST_F(OutboxNodeTest, AMapTheAgentBuiltIsSentAgainAfterARestartAndNumberingGoesOn) {
  const sim::World world = testing::RoomWorld(testing::kPallet);
  std::set<int32_t> first_run;
  {
    RecordingPublisher out;
    auto node = AgentNode::Create(testing::RoomOptions(world, dir_.path()), &out, nullptr,
                                  world.static_map(), 0.0)
                    .value();
    testing::DriveNode(world, *node, 16.0);
    node->Shutdown(16.0);
    for (const auto& t : out.Decoded<fleetmap::tempmap_tile_t>("TEMPMAP_v1"))
      first_run.insert(t.tempmap_seq);
    ASSERT_FALSE(first_run.empty());
    EXPECT_EQ(testing::Counter(*node, "tempmaps_pending"), static_cast<int64_t>(first_run.size()));
  }  // the agent stops without any acknowledgement
  RecordingPublisher out;
  auto node = AgentNode::Create(testing::RoomOptions(world, dir_.path()), &out, nullptr,
                                world.static_map(), 500.0)
                  .value();
  for (double t = 500.0; t < 500.5; t += 0.05) node->Tick(t);
  std::set<int32_t> resent;
  for (const auto& t : out.Decoded<fleetmap::tempmap_tile_t>("TEMPMAP_v1"))
    resent.insert(t.tempmap_seq);
  EXPECT_EQ(resent, first_run);
  // A new map would not reuse a pending number: numbering goes on after the block of 32 that
  // the first run reserved on disk when it started (one fsync per block, not per map).
  ASSERT_LT(first_run.size(), 32u);
  EXPECT_EQ(node->pipeline().options().first_sequence, *first_run.begin() + 32);
  // Once merged, the files are gone and a third start sends nothing.
  for (int32_t s : first_run)
    SendAck(*node, MakeAck(s, fleetmap::tempmap_ack_t::MERGED, {}), 501.0);
  RecordingPublisher third_out;
  auto third = AgentNode::Create(testing::RoomOptions(world, dir_.path()), &third_out, nullptr,
                                 world.static_map(), 600.0)
                   .value();
  third->Tick(600.0);
  EXPECT_EQ(third_out.Count("TEMPMAP_v1"), 0u);
  // ... and after the second run's block.
  EXPECT_EQ(third->pipeline().options().first_sequence, *first_run.begin() + 64);
}

TEST_F(OutboxNodeTest, TileBurstsArePacedAndAcknowledgedTilesLeaveTheQueue) {
  auto node = NodeWithPendingMap({4, 5, 6});  // 36 tiles due at once
  node->Tick(100.0);
  EXPECT_EQ(out_.Count("TEMPMAP_v1"), 16u);  // the pacer's burst
  EXPECT_EQ(testing::Counter(*node, "tiles_queued"), 20);
  // The aggregator already has map 6 (merged, say, before a restart of the agent).
  SendAck(*node, MakeAck(6, fleetmap::tempmap_ack_t::DUPLICATE, {}), 100.0);
  EXPECT_EQ(testing::Counter(*node, "tiles_queued"), 8);
  node->Tick(100.01);  // 400 tiles/s: 4 more
  EXPECT_EQ(out_.Count("TEMPMAP_v1"), 20u);
  for (double t = 100.02; t < 100.9; t += 0.01) node->Tick(t);
  EXPECT_EQ(out_.Count("TEMPMAP_v1"), 24u);  // maps 4 and 5 once each, nothing of 6 twice
  std::set<std::pair<int32_t, int32_t>> sent;
  for (const auto& t : out_.Decoded<fleetmap::tempmap_tile_t>("TEMPMAP_v1"))
    EXPECT_TRUE(sent.insert({t.tempmap_seq, t.tile_index}).second);
  EXPECT_EQ(testing::Counter(*node, "tiles_queued"), 0);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
