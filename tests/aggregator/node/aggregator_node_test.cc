#include "aggregator/node/aggregator_node.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <random>
#include <set>

#include "aggregator/node/map_hash.h"
#include "auth/trailer.h"
#include "core/map/map_replica.h"
#include "fleetmap/map_request_t.hpp"
#include "tests/aggregator/node/node_test_util.h"
#include "tests/aggregator/test_files.h"
#include "vehicle_agent/tempmap_outbox.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::Feed;
using testing::MakeNode;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::SentMessage;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;  // when the vehicle sent its tiles

std::vector<int32_t> Received(const fleetmap::tempmap_ack_t& ack) {
  return std::vector<int32_t>(ack.received_tiles.begin(), ack.received_tiles.end());
}

std::vector<uint8_t> Request(int32_t have_version, std::vector<int32_t> tiles = {}) {
  fleetmap::map_request_t r;
  r.utime = kUtime;
  r.vehicle_id = "v1";
  r.have_version = have_version;
  r.tiles = std::move(tiles);
  r.num_tiles = static_cast<int32_t>(r.tiles.size());
  return Encode(r);
}

void SendRequest(AggregatorNode& node, const std::vector<uint8_t>& bytes, double now_s) {
  node.OnMessage(lcmtypes::kMapRequestChannel, bytes.data(), static_cast<int>(bytes.size()), now_s);
}

// Builds a replica from every keyframe tile, then applies every delta tile, in send order.
core::MapReplica Replay(const RecordingPublisher& out) {
  core::MapReplica replica;
  for (const SentMessage& m : out.sent) {
    const int size = static_cast<int>(auth::PayloadSize(m.bytes.data(), m.bytes.size()));
    if (m.channel == lcmtypes::kMapKeyframeChannel) {
      auto msg = lcmtypes::Decode<fleetmap::map_keyframe_t>(m.bytes.data(), size);
      auto tile = lcmtypes::FromMessage(*msg);
      EXPECT_TRUE(tile.ok()) << tile.status().ToString();
      EXPECT_TRUE(replica.AddKeyframeTile(*tile).ok());
    } else if (m.channel == lcmtypes::kMapDeltaChannel) {
      auto msg = lcmtypes::Decode<fleetmap::map_delta_t>(m.bytes.data(), size);
      auto tile = lcmtypes::FromMessage(*msg);
      EXPECT_TRUE(tile.ok()) << tile.status().ToString();
      EXPECT_TRUE(replica.AddDeltaTile(*tile).ok());
    }
  }
  return replica;
}

// The map as it travels: every tile packed tri-state, which is what a vehicle can hold.
std::vector<core::EncodedTile> Packed(const core::OccupancyGrid& grid) {
  return core::EncodeAllTiles(grid);
}

void ExpectSameMap(const core::OccupancyGrid& a, const core::OccupancyGrid& b) {
  ASSERT_TRUE(a.geometry() == b.geometry());
  const auto pa = Packed(a), pb = Packed(b);
  ASSERT_EQ(pa.size(), pb.size());
  for (size_t i = 0; i < pa.size(); ++i) EXPECT_EQ(pa[i].frame, pb[i].frame) << "tile " << i;
}

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

TEST(AggregatorNodeTest, DeltasAppliedToAKeyframeReplicaGiveTheCurrentMap) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  SendRequest(*node, Request(-1), 1.0);  // a vehicle without a map
  node->Tick(1.0);
  EXPECT_EQ(node->counters().keyframes_sent, 1);
  for (size_t i = 0; i < PalletMaps().size(); ++i) {
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + int64_t(i) * 20'000'000), 2.0 + i);
  }
  const CurrentMapStore& store = node->aggregator().store();
  ASSERT_EQ(store.version(), 4u);
  ASSERT_GT(std::count(store.semi_static().begin(), store.semi_static().end(), 1), 20)
      << "the pallet was confirmed and added";
  EXPECT_GT(node->counters().delta_tiles_sent, 1);
  const core::MapReplica replica = Replay(out);
  ASSERT_TRUE(replica.has_map());
  EXPECT_EQ(replica.version(), 4);
  ExpectSameMap(replica.map(), store.current_map());
}

TEST(AggregatorNodeTest, KeyframeRequestsBuildTheSameMapAndAreCoalesced) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  for (size_t i = 0; i < PalletMaps().size(); ++i) {
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + int64_t(i) * 20'000'000), 1.0);
  }
  out.sent.clear();
  SendRequest(*node, Request(-1), 2.0);
  SendRequest(*node, Request(-1), 2.0);  // another vehicle, same moment
  node->Tick(2.0);
  SendRequest(*node, Request(-1), 2.2);
  node->Tick(2.2);  // within 0.5 s of the last keyframe: waits
  const CurrentMapStore& store = node->aggregator().store();
  const int tiles = core::TileLayout(store.current_map().geometry(), 64).num_tiles();
  EXPECT_EQ(out.Count(lcmtypes::kMapKeyframeChannel), static_cast<size_t>(tiles));
  const core::MapReplica replica = Replay(out);
  ASSERT_TRUE(replica.has_map());
  EXPECT_EQ(replica.version(), 4);
  ExpectSameMap(replica.map(), store.current_map());
  node->Tick(2.5);
  EXPECT_EQ(out.Count(lcmtypes::kMapKeyframeChannel), 2u * tiles);
  EXPECT_EQ(node->counters().keyframes_sent, 2);
  EXPECT_EQ(node->counters().requests, 3);

  out.sent.clear();  // only the tiles a vehicle lacks
  SendRequest(*node, Request(-1, {0, 5}), 4.0);
  SendRequest(*node, Request(-1, {5, 7}), 4.0);
  node->Tick(4.0);
  const auto keyframe = out.Decoded<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel);
  ASSERT_EQ(keyframe.size(), 3u);
  EXPECT_EQ(keyframe[0].tile_index, 0);
  EXPECT_EQ(keyframe[1].tile_index, 5);
  EXPECT_EQ(keyframe[2].tile_index, 7);
  EXPECT_EQ(keyframe[2].tile_count, tiles);
  EXPECT_EQ(keyframe[2].version, 4);
}

TEST(AggregatorNodeTest, RequestFromARetainedVersionGetsTheDeltasSince) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  for (size_t i = 0; i < PalletMaps().size(); ++i) {
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + int64_t(i) * 20'000'000), 1.0);
  }
  // A vehicle holding version 1 (e.g. the keyframe of earlier) gets 1->2, 2->3, 3->4.
  std::vector<SentMessage> version_one;
  {
    RecordingPublisher first;
    auto other = MakeNode(&first);
    SendRequest(*other, Request(-1), 0.0);
    other->Tick(0.0);
    Feed(*other, "v1", TileMessages(PalletMaps()[0], kUtime), 0.5);
    version_one = first.sent;
  }
  out.sent = version_one;
  const size_t before = out.sent.size();
  SendRequest(*node, Request(1), 2.0);
  SendRequest(*node, Request(4), 2.0);  // up to date: nothing to send
  node->Tick(2.0);
  EXPECT_EQ(node->counters().keyframes_sent, 0);
  EXPECT_EQ(node->counters().deltas_resent, 3);
  std::set<int32_t> bases;
  for (size_t i = before; i < out.sent.size(); ++i) {
    if (out.sent[i].channel != lcmtypes::kMapDeltaChannel) continue;
    const std::vector<uint8_t>& bytes = out.sent[i].bytes;
    auto d = lcmtypes::Decode<fleetmap::map_delta_t>(
        bytes.data(), int(auth::PayloadSize(bytes.data(), bytes.size())));
    bases.insert(d->base_version);
  }
  EXPECT_EQ(bases, (std::set<int32_t>{1, 2, 3}));
  const core::MapReplica replica = Replay(out);
  ASSERT_TRUE(replica.has_map());
  EXPECT_EQ(replica.version(), 4);
  ExpectSameMap(replica.map(), node->aggregator().store().current_map());

  // Versions no longer retained, or a vehicle ahead of us: a keyframe instead.
  SendRequest(*node, Request(7), 3.0);
  node->Tick(3.0);
  EXPECT_EQ(node->counters().keyframes_sent, 1);
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

TEST(AggregatorNodeTest, ADuplicateIsRecognisedAfterReopeningTheStateFolder) {
  aggregator::testing::ScratchFolder folder;
  const auto tiles = TileMessages(PalletMaps()[0], kUtime);
  uint64_t hash = 0;
  {
    RecordingPublisher out;
    auto node = MakeNode(&out, {}, folder.path());
    Feed(*node, "v1", tiles, 1.0);
    Feed(*node, "v1", TileMessages(PalletMaps()[1], kUtime + 20'000'000), 1.5);
    ASSERT_EQ(node->aggregator().store().version(), 2u);
    hash = MapHash(node->aggregator().store().current_map());
  }
  RecordingPublisher out;
  auto node = MakeNode(&out, {}, folder.path());
  ASSERT_EQ(node->aggregator().store().version(), 2u);
  Feed(*node, "v1", tiles, 2.0);
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::DUPLICATE);
  EXPECT_EQ(acks[0].map_version, 1);
  EXPECT_EQ(node->aggregator().store().version(), 2u);
  EXPECT_EQ(MapHash(node->aggregator().store().current_map()), hash);
}

TEST(AggregatorNodeTest, AcknowledgedTilesOfAnIncompleteMapSurviveARestart) {
  aggregator::testing::ScratchFolder folder;
  const auto tiles = TileMessages(PalletMaps()[0], kUtime);
  {
    RecordingPublisher out;
    auto node = MakeNode(&out, {}, folder.path());
    Feed(*node, "v1", std::vector<std::vector<uint8_t>>(tiles.begin(), tiles.end() - 1), 1.0);
    node->Tick(1.5);
    const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
    ASSERT_EQ(acks.size(), 1u);
    EXPECT_EQ(acks[0].num_received, static_cast<int32_t>(tiles.size()) - 1);
  }  // killed: the vehicle will never send those tiles again, only the last one
  RecordingPublisher out;
  auto node = MakeNode(&out, {}, folder.path(), {}, 2.0);
  EXPECT_EQ(node->incomplete_maps(), 1u);
  Feed(*node, "v1", {tiles.back()}, 2.5);
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_EQ(node->aggregator().store().version(), 1u);
  EXPECT_TRUE(std::filesystem::is_empty(folder.File("incoming")));  // forgotten once merged
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

TEST(AggregatorNodeTest, AFailedJournalWriteAcknowledgesNothingAndTheResendMerges) {
  aggregator::testing::ScratchFolder folder;
  RecordingPublisher out;
  auto node = MakeNode(&out, {}, folder.path());
  const auto tiles = TileMessages(PalletMaps()[0], kUtime);
  {
    aggregator::testing::FileSizeLimit full_disk(16);  // the journal cannot grow
    Feed(*node, "v1", tiles, 1.0);
  }
  EXPECT_EQ(out.Count(lcmtypes::kTempMapAckChannel), 0u);
  EXPECT_EQ(node->counters().persist_errors, 1);
  EXPECT_EQ(node->state(), "persist_failed");
  EXPECT_EQ(node->aggregator().store().version(), 0u);
  node->Tick(1.1);
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_aggregator");
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(status[0].state, "persist_failed");
  Feed(*node, "v1", {tiles[0]}, 2.0);  // the vehicle resends; the disk has room again
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_EQ(node->state(), "running");
  EXPECT_EQ(node->aggregator().store().version(), 1u);
}

// The disk fills while two vehicles' maps come in, then space returns: the maps that waited
// are merged within a second, in the order they arrived, and the map is the one a node
// without the fault made from the same maps (as a replay of the uplink log would).
TEST(AggregatorNodeTest, AfterAFullDiskTheBacklogMergesInArrivalOrderAsWithoutTheFault) {
  aggregator::testing::ScratchFolder folder;
  RecordingPublisher out, reference_out;
  auto node = MakeNode(&out, {}, folder.path());
  auto reference = MakeNode(&reference_out, {}, "");
  std::vector<std::pair<std::string, std::vector<std::vector<uint8_t>>>> maps;
  for (int i = 0; i < 4; ++i) {
    core::TempMap m = PalletMaps()[i];
    m.vehicle_id = i % 2 ? "v2" : "v1";
    maps.emplace_back(m.vehicle_id, TileMessages(m, kUtime + 20'000'000LL * i));
  }
  Feed(*node, maps[0].first, maps[0].second, 1.0);
  {
    aggregator::testing::FileSizeLimit full_disk(16);  // the journal cannot grow
    for (int i = 1; i < 4; ++i) Feed(*node, maps[i].first, maps[i].second, 1.0 + i);
    node->Tick(4.5);  // tried again: still full
  }
  EXPECT_EQ(out.Count(lcmtypes::kTempMapAckChannel), 1u);
  EXPECT_EQ(node->state(), "persist_failed");
  node->Tick(5.5);  // space is back: everything waiting merges at the next try
  EXPECT_EQ(node->state(), "running");
  for (int i = 0; i < 4; ++i) Feed(*reference, maps[i].first, maps[i].second, 1.0 + i);
  const auto order = [](const RecordingPublisher& o) {
    std::vector<std::string> keys;
    for (const auto& a : o.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel))
      keys.push_back(a.vehicle_id + "#" + std::to_string(a.tempmap_seq) + ":" +
                     std::to_string(a.outcome));
    return keys;
  };
  EXPECT_EQ(order(out), order(reference_out));
  ASSERT_EQ(order(out).size(), 4u);
  const auto map_part = [](const std::string& line) {
    return line.substr(0, line.find(" merged"));
  };
  EXPECT_EQ(map_part(node->FinalLine()), map_part(reference->FinalLine()));
}

// Two vehicles' four maps merged, then the state folder lost (the worst damage: recovered
// at version 0). The restarted aggregator names the recovery in its STATUS; the vehicles send
// again what they kept, in the order they first sent it: every acknowledged merge is back,
// and the map is the one before the loss.
TEST(AggregatorNodeTest, AfterARecoveryTheVehiclesKeptMapsBringBackEveryAcknowledgedMerge) {
  aggregator::testing::ScratchFolder folder;
  std::map<std::string, vehicle_agent::TempMapOutbox> vehicles;
  vehicles.emplace("v1", vehicle_agent::OutboxOptions{});
  vehicles.emplace("v2", vehicle_agent::OutboxOptions{});
  std::vector<std::pair<std::string, int32_t>> sent_order;
  // Sends what each vehicle has due, in `sent_order`, and hands the acknowledgements back.
  const auto exchange = [&](AggregatorNode& node, RecordingPublisher& out, double now_s) {
    const size_t acks_before = out.Count(lcmtypes::kTempMapAckChannel);
    std::map<std::pair<std::string, int32_t>, std::vector<std::vector<uint8_t>>> due;
    for (auto& [id, outbox] : vehicles) {
      for (const core::TempMapTile& t : outbox.Due(now_s)) {
        const int64_t utime = kUtime + int64_t{20'000'000} * t.sequence + (now_s > 50 ? 1 : 0);
        due[{id, t.sequence}].push_back(Encode(lcmtypes::ToMessage(t, utime)));
      }
    }
    for (const auto& key : sent_order)
      if (due.count(key)) Feed(node, key.first, due[key], now_s);
    const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
    for (size_t i = acks_before; i < acks.size(); ++i) {
      const fleetmap::tempmap_ack_t& a = acks[i];
      vehicles.at(a.vehicle_id)
          .OnAck(a.tempmap_seq, Received(a), static_cast<vehicle_agent::AckOutcome>(a.outcome),
                 a.map_version);
    }
  };
  uint64_t hash = 0;
  {
    RecordingPublisher out;
    auto node = MakeNode(&out, {}, folder.path());
    for (int i = 0; i < 4; ++i) {
      core::TempMap m = PalletMaps()[i];
      m.vehicle_id = i % 2 ? "v2" : "v1";
      sent_order.emplace_back(m.vehicle_id, m.sequence);
      ASSERT_TRUE(vehicles.at(m.vehicle_id).Add(m, 1.0 + i).ok());
      exchange(*node, out, 1.0 + i);
    }
    ASSERT_EQ(node->counters().maps_merged, 4);
    hash = MapHash(node->aggregator().store().current_map());
  }
  for (auto& [id, outbox] : vehicles) {
    EXPECT_EQ(outbox.pending(), 0u) << id;
    EXPECT_EQ(outbox.retained().size(), 2u) << id;
  }
  std::filesystem::remove(folder.File(aggregator::MapPersistence::kSnapshotName));
  std::filesystem::remove(folder.File(aggregator::MapPersistence::kJournalName));

  RecordingPublisher out;
  AggregatorNodeOptions options;
  options.recovery = {42, 0, 1000.0};
  auto node = MakeNode(&out, {}, folder.path(), options, 100.0);
  ASSERT_EQ(node->aggregator().store().version(), 0u);
  node->Tick(100.0);
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_aggregator");
  ASSERT_FALSE(status.empty());
  const auto counter = [&](const std::string& name) {
    const auto& s = status.back();
    for (size_t i = 0; i < s.counter_names.size(); ++i)
      if (s.counter_names[i] == name) return s.counter_values[i];
    return int64_t{-1};
  };
  EXPECT_EQ(counter(lcmtypes::kRecoveryIdCounter), 42);
  EXPECT_EQ(counter(lcmtypes::kRecoveredVersionCounter), 0);
  for (auto& [id, outbox] : vehicles) EXPECT_EQ(outbox.ResendMergedAfter(0, 100.0), 2) << id;
  exchange(*node, out, 100.0);
  EXPECT_EQ(node->counters().maps_merged, 4);
  EXPECT_EQ(node->aggregator().store().version(), 4u);
  EXPECT_EQ(MapHash(node->aggregator().store().current_map()), hash);
  for (auto& [id, outbox] : vehicles) EXPECT_EQ(outbox.pending(), 0u) << id;

  // After the request's window, STATUS no longer names it.
  node->Tick(1000.5);
  const auto later = out.Decoded<fleetmap::status_t>("STATUS_aggregator").back();
  EXPECT_EQ(std::count(later.counter_names.begin(), later.counter_names.end(),
                       lcmtypes::kRecoveryIdCounter),
            0);
}

TEST(AggregatorNodeTest, StatusEverySecondAndAKeyframeEveryPeriod) {
  RecordingPublisher out;
  AggregatorNodeOptions options;
  options.keyframe_period_s = 10.0;
  auto node = MakeNode(&out, {}, "", options, 100.0);
  for (double t = 100.0; t < 121.0; t += 0.1) node->Tick(t);
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_aggregator");
  EXPECT_NEAR(static_cast<double>(status.size()), 21.0, 1.0);
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status[0].process, "aggregator");
  EXPECT_EQ(status[0].state, "running");
  EXPECT_FALSE(status[0].authenticated);
  EXPECT_EQ(status[0].map_version, 0);
  EXPECT_EQ(status[0].num_counters, static_cast<int32_t>(status[0].counter_names.size()));
  for (const char* name :
       {"tiles_received", "maps_completed", "maps_merged", "maps_rejected", "duplicates",
        "malformed_messages", "wrong_vehicle_id", "unknown_channel", "requests", "keyframes_sent",
        "delta_tiles_sent", "persist_errors"}) {
    EXPECT_EQ(std::count(status[0].counter_names.begin(), status[0].counter_names.end(), name), 1)
        << name;
  }
  EXPECT_EQ(node->counters().keyframes_sent, 2);  // at 110 s and 120 s
  for (const SentMessage& m : out.sent) EXPECT_EQ(m.link, Link::kDownlink) << m.channel;
}

TEST(AggregatorNodeTest, EveryMessageStaysAFewKilobytes) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  auto tiles = TileMessages(PalletMaps()[0], kUtime);
  Feed(*node, "v1", {tiles[0]}, 1.0);
  node->Tick(1.5);  // a PENDING acknowledgement
  Feed(*node, "v1", tiles, 1.6);
  for (size_t i = 1; i < PalletMaps().size(); ++i)
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + int64_t(i) * 20'000'000), 2.0);
  SendRequest(*node, Request(-1), 3.0);
  node->Tick(3.0);
  size_t largest = 0;
  for (const SentMessage& m : out.sent) largest = std::max(largest, m.bytes.size());
  EXPECT_LE(largest, 8192u);
  EXPECT_EQ(node->counters().oversize_messages, 0);
  for (const auto& [channel, bytes] : node->largest_messages()) {
    std::printf("largest %s message: %zu B\n", channel.c_str(), bytes);
    ::testing::Test::RecordProperty("largest_" + channel + "_bytes", static_cast<int>(bytes));
  }
  for (const auto& t : tiles) EXPECT_LE(t.size(), 8192u) << "a temporary-map tile";
}

}  // namespace
}  // namespace fleetmap::aggregator::node
