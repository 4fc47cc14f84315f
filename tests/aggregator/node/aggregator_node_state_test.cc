// AggregatorNode on a state folder: what it acknowledged survives a restart, a full disk
// acknowledges nothing until the journal can grow again and then merges the backlog as if
// nothing had happened, and after a recovery the vehicles' kept maps bring back every
// acknowledged merge.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "aggregator/node/aggregator_node.h"
#include "aggregator/node/map_hash.h"
#include "tests/aggregator/node/node_test_util.h"
#include "tests/aggregator/test_files.h"
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

TEST(AggregatorNodeTest, ADuplicateIsRecognisedAfterReopeningTheStateFolder) {
  fleetmap::testing::ScratchFolder folder;
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
  fleetmap::testing::ScratchFolder folder;
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

TEST(AggregatorNodeTest, AFailedJournalWriteAcknowledgesNothingAndTheResendMerges) {
  fleetmap::testing::ScratchFolder folder;
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
  fleetmap::testing::ScratchFolder folder;
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
  fleetmap::testing::ScratchFolder folder;
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

}  // namespace
}  // namespace fleetmap::aggregator::node
