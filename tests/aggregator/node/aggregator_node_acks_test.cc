// AggregatorNode in memory, its answers to the uplink: a temporary map's tiles acknowledged
// as they come (PENDING, at most once per interval and only with news) and the map's outcome
// once complete (MERGED, REJECTED with its reason, DUPLICATE for a map sent again), with the
// merge report beside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "aggregator/node/aggregator_node.h"
#include "tests/aggregator/node/node_test_util.h"
#include "vehicle_agent/tempmap_outbox.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::Feed;
using testing::MakeNode;
using testing::PalletMaps;
using testing::Received;
using testing::RecordingPublisher;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;  // when the vehicle sent its tiles

TEST(AggregatorNodeTest, TilesInAnyOrderWithRepeatsAndALostOneArePendingThenMerged) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  auto tiles = TileMessages(PalletMaps()[0], kUtime);
  ASSERT_GE(tiles.size(), 4u);
  std::vector<size_t> order(tiles.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(3));
  const size_t lost = order.back();
  order.pop_back();
  order.insert(order.begin() + 3, order[1]);  // one tile twice in the burst
  for (size_t i : order) Feed(*node, "v1", {tiles[i]}, 100.0);
  EXPECT_EQ(out.Count(lcmtypes::kTempMapAckChannel), 1u);  // the repeat asked for one

  // The vehicle's outbox learns which tiles arrived and resends only the lost one.
  vehicle_agent::OutboxOptions outbox_options;
  vehicle_agent::TempMapOutbox outbox(outbox_options);
  ASSERT_TRUE(outbox.Add(PalletMaps()[0], 100.0).ok());
  ASSERT_EQ(outbox.Due(100.0).size(), tiles.size());
  node->Tick(100.6);
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 2u);
  // The first, at the repeat, names the three tiles in by then; the second all but the lost.
  EXPECT_EQ(acks[0].num_received, 3);
  EXPECT_EQ(acks[1].num_received, static_cast<int32_t>(tiles.size()) - 1);
  for (const auto& ack : acks) {
    EXPECT_EQ(ack.outcome, fleetmap::tempmap_ack_t::PENDING);
    EXPECT_EQ(ack.vehicle_id, "v1");
    EXPECT_EQ(ack.tempmap_seq, 1);
    EXPECT_EQ(ack.tile_count, static_cast<int32_t>(tiles.size()));
    EXPECT_EQ(ack.num_received, static_cast<int32_t>(ack.received_tiles.size()));
    const auto received = Received(ack);
    EXPECT_EQ(std::count(received.begin(), received.end(), static_cast<int32_t>(lost)), 0);
    outbox.OnAck(ack.tempmap_seq, received, vehicle_agent::AckOutcome::kPending);
  }
  node->Tick(100.8);  // nothing new: no more acknowledgements
  EXPECT_EQ(out.Count(lcmtypes::kTempMapAckChannel), 2u);
  const auto resend = outbox.Due(101.0);
  ASSERT_EQ(resend.size(), 1u);
  EXPECT_EQ(resend[0].index, static_cast<int32_t>(lost));
  EXPECT_EQ(node->aggregator().store().version(), 0u);

  Feed(*node, "v1", {Encode(lcmtypes::ToMessage(resend[0], kUtime + 1'000'000))}, 101.0);
  const auto final_acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(final_acks.size(), 3u);
  EXPECT_EQ(final_acks[2].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_EQ(final_acks[2].map_version, 1);
  outbox.OnAck(1, {}, vehicle_agent::AckOutcome::kMerged);
  EXPECT_EQ(outbox.pending(), 0u);
  EXPECT_EQ(node->aggregator().store().version(), 1u);
  EXPECT_EQ(node->counters().maps_merged, 1);
  EXPECT_EQ(node->counters().tiles_repeated, 1);

  const auto reports = out.Decoded<fleetmap::merge_report_t>(lcmtypes::kMergeReportChannel);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_TRUE(reports[0].accepted);
  EXPECT_EQ(reports[0].new_version, 1);
  EXPECT_EQ(reports[0].num_matches, static_cast<int32_t>(reports[0].matches.size()));
  EXPECT_GT(reports[0].num_matches, 0);
  EXPECT_GT(reports[0].score, 0.0);
  EXPECT_EQ(reports[0].utime, kUtime + 1'000'000);  // the completing tile's time
  // The anchor was 0.1 m off in x and y and 1.5 deg off: the correction undoes it.
  EXPECT_NEAR(reports[0].dx_m, 0.1, 0.06);
  EXPECT_NEAR(reports[0].dy_m, 0.1, 0.06);
  EXPECT_NEAR(reports[0].dtheta_rad, 1.5 * M_PI / 180, 0.5 * M_PI / 180);
  // The first sight of the pallet makes candidates (two sightings add it): no cell
  // changed, yet vehicles must advance, so one delta message with no tile.
  const auto deltas = out.Decoded<fleetmap::map_delta_t>(lcmtypes::kMapDeltaChannel);
  ASSERT_EQ(deltas.size(), 1u);
  EXPECT_EQ(deltas[0].base_version, 0);
  EXPECT_EQ(deltas[0].new_version, 1);
  EXPECT_EQ(deltas[0].tile_count, 0);
}

TEST(AggregatorNodeTest, AMapCompleteInOneBurstGetsNoPendingAcknowledgement) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  Feed(*node, "v1", TileMessages(PalletMaps()[0], kUtime), 5.0);
  node->Tick(5.1);
  node->Tick(6.0);
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_EQ(node->counters().pending_acks_sent, 0);
}

TEST(AggregatorNodeTest, PendingAcknowledgementsWaitForTheIntervalAndOnlyForNews) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  auto tiles = TileMessages(PalletMaps()[0], kUtime);
  Feed(*node, "v1", {tiles[0], tiles[1]}, 10.0);
  node->Tick(10.3);
  EXPECT_EQ(node->counters().pending_acks_sent, 0);  // the rest of the burst may come
  node->Tick(10.5);
  EXPECT_EQ(node->counters().pending_acks_sent, 1);
  node->Tick(11.5);
  EXPECT_EQ(node->counters().pending_acks_sent, 1);  // nothing new
  Feed(*node, "v1", {tiles[2]}, 11.6);
  node->Tick(11.7);
  EXPECT_EQ(node->counters().pending_acks_sent, 2);  // news, and the interval has passed
  Feed(*node, "v1", {tiles[3]}, 11.8);
  node->Tick(11.9);
  EXPECT_EQ(node->counters().pending_acks_sent, 2);  // news, but within 0.5 s of the last
  node->Tick(12.2);
  EXPECT_EQ(node->counters().pending_acks_sent, 3);
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  EXPECT_EQ(Received(acks.back()), (std::vector<int32_t>{0, 1, 2, 3}));
}

TEST(AggregatorNodeTest, AMapSentAgainAfterItsMergeIsADuplicate) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  const auto tiles = TileMessages(PalletMaps()[0], kUtime);
  Feed(*node, "v1", tiles, 1.0);
  ASSERT_EQ(node->aggregator().store().version(), 1u);
  Feed(*node, "v1", tiles, 3.0);  // the MERGED acknowledgement was lost
  Feed(*node, "v1", tiles, 3.2);  // ... twice; one answer per interval
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[1].outcome, fleetmap::tempmap_ack_t::DUPLICATE);
  EXPECT_EQ(acks[1].map_version, 1);  // the version that holds it
  EXPECT_EQ(node->aggregator().store().version(), 1u);
  EXPECT_EQ(node->counters().maps_merged, 1);
  EXPECT_EQ(node->counters().duplicates, 2 * static_cast<int64_t>(tiles.size()));
  node->Tick(3.5);
  Feed(*node, "v1", {tiles[0]}, 3.9);
  EXPECT_EQ(out.Count(lcmtypes::kTempMapAckChannel), 3u);
}

TEST(AggregatorNodeTest, ARejectedMapIsAnsweredWithTheReasonAndThenAsDuplicate) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  core::TempMap far = PalletMaps()[0];
  far.sequence = 9;
  far.anchor_in_map = core::Pose2(far.anchor_in_map.x_m + 30.0, far.anchor_in_map.y_m, 0.0);
  const auto tiles = TileMessages(far, kUtime);
  Feed(*node, "v1", tiles, 1.0);
  Feed(*node, "v1", tiles, 2.0);
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::REJECTED);
  EXPECT_FALSE(acks[0].reason.empty());
  EXPECT_EQ(acks[1].outcome, fleetmap::tempmap_ack_t::DUPLICATE);
  const auto reports = out.Decoded<fleetmap::merge_report_t>(lcmtypes::kMergeReportChannel);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_FALSE(reports[0].accepted);
  EXPECT_EQ(reports[0].reason, acks[0].reason);
  EXPECT_EQ(reports[0].new_version, 0);
  EXPECT_EQ(out.Count(lcmtypes::kMapDeltaChannel), 0u);
  EXPECT_EQ(node->counters().maps_rejected, 1);
  EXPECT_EQ(node->aggregator().store().version(), 0u);
}

}  // namespace
}  // namespace fleetmap::aggregator::node
