// AggregatorNode in memory, what it sends on the downlink: the deltas of every merge, and
// keyframe tiles and retained deltas for the vehicles that ask (MAP_REQUEST), which rebuild
// exactly the current map; STATUS every second and the rolling keyframe; every message a few
// kilobytes at most.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>

#include "aggregator/node/aggregator_node.h"
#include "auth/trailer.h"
#include "core/map/map_replica.h"
#include "fleetmap/map_request_t.hpp"
#include "tests/aggregator/node/node_test_util.h"

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

std::vector<uint8_t> Request(int32_t have_version, std::vector<int32_t> tiles = {}) {
  fleetmap::map_request_t r;
  r.utime = kUtime;
  r.vehicle_id = "v1";
  r.have_version = have_version;
  r.tiles = std::move(tiles);
  r.num_tiles = static_cast<int32_t>(r.tiles.size());
  return Encode(r);
}

// Without the rolling keyframe: the keyframe tiles sent are those asked for.
AggregatorNodeOptions OnlyAskedKeyframes() {
  AggregatorNodeOptions options;
  options.keyframe_period_s = 0.0;
  return options;
}

int TileCount(const AggregatorNode& node) {
  return core::TileLayout(node.aggregator().store().current_map().geometry(), 64).num_tiles();
}

void SendRequest(AggregatorNode& node, const std::vector<uint8_t>& bytes, double now_s) {
  node.OnMessage(lcmtypes::kMapRequestChannel, bytes.data(), static_cast<int>(bytes.size()), now_s);
}

// Decodes one tile message of type Message and hands the tile to `add`.
template <typename Message, typename Add>
core::Status DeliverTile(const SentMessage& m, Add add) {
  auto msg = lcmtypes::Decode<Message>(
      m.bytes.data(), static_cast<int>(auth::PayloadSize(m.bytes.data(), m.bytes.size())));
  if (!msg.ok()) return msg.status();
  auto tile = lcmtypes::FromMessage(*msg);
  if (!tile.ok()) return tile.status();
  return add(*tile).status();
}

// Hands one downlink message to a vehicle's replica: keyframe and delta tiles; others ignored.
core::Status Deliver(const SentMessage& m, core::MapReplica& replica) {
  if (m.channel == lcmtypes::kMapKeyframeChannel)
    return DeliverTile<fleetmap::map_keyframe_t>(
        m, [&](const core::KeyframeTile& t) { return replica.AddKeyframeTile(t); });
  if (m.channel == lcmtypes::kMapDeltaChannel)
    return DeliverTile<fleetmap::map_delta_t>(
        m, [&](const core::DeltaTile& t) { return replica.AddDeltaTile(t); });
  return core::OkStatus();
}

// Builds a replica from every keyframe tile, then applies every delta tile, in send order.
core::MapReplica Replay(const RecordingPublisher& out) {
  core::MapReplica replica;
  for (const SentMessage& m : out.sent) {
    const core::Status s = Deliver(m, replica);
    EXPECT_TRUE(s.ok()) << m.channel << ": " << s.ToString();
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

TEST(AggregatorNodeTest, DeltasAppliedToAKeyframeReplicaGiveTheCurrentMap) {
  RecordingPublisher out;
  auto node = MakeNode(&out, {}, "", OnlyAskedKeyframes());
  SendRequest(*node, Request(-1), 1.0);  // a vehicle without a map
  node->Tick(1.0);
  EXPECT_EQ(node->counters().asked_tiles_sent, TileCount(*node));
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
  auto node = MakeNode(&out, {}, "", OnlyAskedKeyframes());
  for (size_t i = 0; i < PalletMaps().size(); ++i) {
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + int64_t(i) * 20'000'000), 1.0);
  }
  out.sent.clear();
  SendRequest(*node, Request(-1), 2.0);
  SendRequest(*node, Request(-1), 2.0);  // another vehicle, same moment: one answer
  node->Tick(2.0);
  const CurrentMapStore& store = node->aggregator().store();
  const int tiles = TileCount(*node);
  EXPECT_EQ(out.Count(lcmtypes::kMapKeyframeChannel), static_cast<size_t>(tiles));
  const core::MapReplica replica = Replay(out);
  ASSERT_TRUE(replica.has_map());
  EXPECT_EQ(replica.version(), 4);
  ExpectSameMap(replica.map(), store.current_map());
  SendRequest(*node, Request(-1), 2.2);  // after the answer went: answered again
  node->Tick(2.2);
  EXPECT_EQ(out.Count(lcmtypes::kMapKeyframeChannel), 2u * tiles);
  EXPECT_EQ(node->counters().asked_tiles_sent, 2 * tiles);
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
  auto node = MakeNode(&out, {}, "", OnlyAskedKeyframes());
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
  EXPECT_EQ(node->counters().asked_tiles_sent, 0);
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
  EXPECT_EQ(node->counters().asked_tiles_sent, TileCount(*node));
}

TEST(AggregatorNodeTest, StatusEverySecondAndARollingKeyframeRoundEveryPeriod) {
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
        "malformed_messages", "wrong_vehicle_id", "unknown_channel", "requests",
        "keyframe_tiles_sent", "delta_tiles_sent", "persist_errors"}) {
    EXPECT_EQ(std::count(status[0].counter_names.begin(), status[0].counter_names.end(), name), 1)
        << name;
  }
  EXPECT_EQ(node->counters().keyframe_rounds, 2);  // 21 s at one round per 10 s
  EXPECT_NEAR(static_cast<double>(node->counters().keyframe_tiles_sent), 2.1 * TileCount(*node),
              2.0);
  for (const SentMessage& m : out.sent) EXPECT_EQ(m.link, Link::kDownlink) << m.channel;
}

// A vehicle joining without a map over a link that loses every third message, while the map
// changes twice: it asks for the whole map, then once a second for the tiles it still lacks
// (or, holding a map, for the deltas since its version, as agents do), and the rolling
// keyframe fills in meanwhile. It ends with the current map.
TEST(AggregatorNodeTest, AVehicleJoiningOverALossyLinkEndsWithTheCurrentMap) {
  RecordingPublisher out;
  auto node = MakeNode(&out);  // the rolling keyframe on, as deployed
  for (size_t i = 0; i < 2; ++i)
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + int64_t(i) * 20'000'000), 1.0);
  const CurrentMapStore& store = node->aggregator().store();
  ASSERT_EQ(store.version(), 2u);
  core::MapReplica replica;
  size_t next = out.sent.size();  // the vehicle joins now
  size_t lost = 0;
  double t = 2.0;
  const auto current = [&] {
    return replica.has_map() && !replica.NeedsKeyframe() &&
           replica.version() == static_cast<int32_t>(store.version());
  };
  for (int tick = 0; tick < 300 && !(tick > 20 && current()); ++tick) {
    t += 0.1;
    if (tick % 10 == 0 && !replica.has_map())
      SendRequest(*node, Request(-1, replica.MissingKeyframeTiles()), t);
    if (tick % 10 == 0 && replica.has_map() && replica.NeedsKeyframe())
      SendRequest(*node, Request(replica.version()), t);
    if (tick == 15 || tick == 16) {
      const size_t i = static_cast<size_t>(tick - 13);  // versions 3 and 4
      Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + int64_t(i) * 20'000'000), t);
    }
    node->Tick(t);
    for (; next < out.sent.size(); ++next) {
      if (next % 3 == 0) {
        ++lost;
        continue;
      }
      (void)Deliver(out.sent[next], replica);  // refusals (a version gap too long) are normal
    }
  }
  ASSERT_EQ(store.version(), 4u);
  EXPECT_GT(lost, 10u);
  ASSERT_TRUE(current()) << "after 30 s: version " << replica.version();
  ExpectSameMap(replica.map(), store.current_map());
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
