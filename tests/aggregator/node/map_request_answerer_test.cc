// Catching vehicles up (map_request_answerer.h), driven directly with MAP_REQUEST payloads:
// deltas from a retained version, keyframe tiles asked for sent once however many ask and only
// while the downlink has room, impossible requests refused, and the rolling keyframe.
#include "aggregator/node/map_request_answerer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>

#include "tests/aggregator/node/node_parts_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::KeyOf;
using testing::NodeParts;
using testing::PalletMaps;
using testing::SentMessage;
using testing::TileCount;

constexpr double kStampS = 1.7e9;

struct Answering {
  explicit Answering(AggregatorNodeOptions options = {})
      : parts(std::move(options)),
        answerer(parts.aggregator, parts.options, parts.publisher, parts.report(), 0.0) {}
  // Merges the first `n` pallet maps: versions 1 to n.
  void Merge(size_t n) {
    for (size_t i = 0; i < n; ++i) {
      const core::TempMap& map = PalletMaps()[i];
      parts.committer.Complete(KeyOf(map), map, TileCount(map),
                               kStampS + 20.0 * static_cast<double>(i), 1.0);
    }
    ASSERT_EQ(parts.aggregator.store().version(), n);
    parts.out.sent.clear();
  }
  void Ask(int32_t have_version, std::vector<int32_t> tiles = {},
           const std::string& vehicle = "v1") {
    fleetmap::map_request_t r;
    r.vehicle_id = vehicle;
    r.have_version = have_version;
    r.tiles = std::move(tiles);
    r.num_tiles = static_cast<int32_t>(r.tiles.size());
    const std::vector<uint8_t> bytes = Encode(r);
    answerer.OnRequest(bytes.data(), static_cast<int>(bytes.size()));
  }
  std::vector<int32_t> KeyframeTiles() const {
    std::vector<int32_t> tiles;
    for (const auto& k : parts.out.Decoded<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel))
      tiles.push_back(k.tile_index);
    return tiles;
  }

  NodeParts parts;
  MapRequestAnswerer answerer;
};

TEST(MapRequestAnswererTest, ARetainedVersionIsAnsweredWithTheDeltasSinceTheOldestAskedFor) {
  Answering a;
  a.Merge(3);
  a.Ask(2);
  a.Ask(1);
  a.Ask(3);  // up to date: nothing to send
  EXPECT_EQ(a.parts.counters.requests, 3);
  EXPECT_TRUE(a.parts.out.sent.empty());  // answered at the tick
  a.answerer.Tick(2.0);
  std::set<int32_t> bases;
  for (const auto& d : a.parts.out.Decoded<fleetmap::map_delta_t>(lcmtypes::kMapDeltaChannel))
    bases.insert(d.base_version);
  EXPECT_EQ(bases, (std::set<int32_t>{1, 2}));
  EXPECT_EQ(a.parts.counters.deltas_resent, 2);
  EXPECT_EQ(a.parts.counters.asked_tiles_sent, 0);
}

AggregatorNodeOptions NoRollingKeyframe() {
  AggregatorNodeOptions options;
  options.keyframe_period_s = 0.0;
  return options;
}

TEST(MapRequestAnswererTest, KeyframeTilesAskedForGoOnceHoweverManyVehiclesAsk) {
  Answering a(NoRollingKeyframe());
  a.Ask(0, {5});
  a.Ask(0, {1, 5}, "v2");
  a.Ask(0, {5});
  a.answerer.Tick(1.0);
  EXPECT_EQ(a.KeyframeTiles(), (std::vector<int32_t>{1, 5}));
  EXPECT_EQ(a.parts.counters.asked_tiles_sent, 2);
  a.parts.out.sent.clear();
  a.Ask(4);  // a vehicle ahead of us (our state was lost): the whole map
  a.Ask(-1, {}, "v2");
  a.answerer.Tick(1.1);
  const std::vector<int32_t> tiles = a.KeyframeTiles();
  ASSERT_GT(tiles.size(), 3u);
  EXPECT_EQ(std::set<int32_t>(tiles.begin(), tiles.end()).size(), tiles.size()) << "each once";
  EXPECT_EQ(tiles.size(),
            static_cast<size_t>(
                a.parts.out.Decoded<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel)[0]
                    .tile_count));
}

// Keyframe tiles wait while the downlink has no room (its budget spent, or messages queued);
// the deltas asked for do not wait for them.
TEST(MapRequestAnswererTest, KeyframeTilesWaitForRoomDeltasDoNot) {
  Answering a(NoRollingKeyframe());
  a.Merge(2);
  a.parts.out.room_bytes = 0;
  a.Ask(-1, {}, "new");
  a.Ask(1, {}, "behind");
  a.answerer.Tick(1.0);
  EXPECT_TRUE(a.KeyframeTiles().empty());
  EXPECT_EQ(a.parts.counters.deltas_resent, 1) << "the delta 1 -> 2";
  EXPECT_GT(a.parts.out.Count(lcmtypes::kMapDeltaChannel), 0u);
  EXPECT_GT(a.answerer.tiles_waiting(), 0);
  EXPECT_TRUE(a.answerer.sending());
  const int32_t waiting = a.answerer.tiles_waiting();
  a.parts.out.room_bytes = std::numeric_limits<size_t>::max();
  a.answerer.Tick(1.1);
  EXPECT_EQ(static_cast<int32_t>(a.KeyframeTiles().size()), waiting);
  EXPECT_EQ(a.answerer.tiles_waiting(), 0);
  for (const auto& k : a.parts.out.Decoded<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel))
    EXPECT_EQ(k.version, 2) << "cut from the map when sent";
}

TEST(MapRequestAnswererTest, ARequestTheMapCannotAnswerIsRefusedCountedAndLoggedOnce) {
  Answering a(NoRollingKeyframe());
  a.Ask(-2);
  a.Ask(0, {1 << 20});
  a.Ask(0, {}, std::string(100, 'v'));
  const std::vector<uint8_t> garbage = {1, 2, 3};
  a.answerer.OnRequest(garbage.data(), static_cast<int>(garbage.size()));
  EXPECT_EQ(a.parts.counters.bad_requests, 3);
  EXPECT_EQ(a.parts.counters.malformed_messages, 1);
  EXPECT_EQ(a.parts.counters.requests, 0);
  EXPECT_EQ(a.parts.lines.Containing("refused: have_version"), 1);
  a.answerer.Tick(1.0);
  EXPECT_TRUE(a.parts.out.sent.empty());
}

// Unasked, every tile goes in turn, one round per period, spread over it (no burst), and the
// candidates once per period.
TEST(MapRequestAnswererTest, TheRollingKeyframeSendsEveryTileInTurnOnceAPeriod) {
  AggregatorNodeOptions options;
  options.keyframe_period_s = 10.0;
  Answering a(options);
  size_t most_in_one_tick = 0;
  for (int tick = 1; tick <= 102; ++tick) {  // 10.2 s
    const size_t before = a.parts.out.Count(lcmtypes::kMapKeyframeChannel);
    a.answerer.Tick(0.1 * tick);
    most_in_one_tick =
        std::max(most_in_one_tick, a.parts.out.Count(lcmtypes::kMapKeyframeChannel) - before);
  }
  const std::vector<int32_t> tiles = a.KeyframeTiles();
  ASSERT_FALSE(tiles.empty());
  const int32_t count =
      a.parts.out.Decoded<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel)[0].tile_count;
  ASSERT_GE(tiles.size(), static_cast<size_t>(count));
  EXPECT_LE(tiles.size(), static_cast<size_t>(count) * 103 / 100 + 1);
  for (int32_t i = 0; i < count; ++i) EXPECT_EQ(tiles[i], i);
  EXPECT_EQ(a.parts.counters.keyframe_rounds, 1);
  EXPECT_LE(most_in_one_tick, static_cast<size_t>(count / 10 + 1));
  EXPECT_EQ(a.parts.counters.candidate_sets_sent, 1);
  EXPECT_EQ(a.parts.counters.asked_tiles_sent, 0);
}

// On a large map the rolling keyframe would fill the channel: it takes at most its share of
// the budget (its round lasts longer), while tiles asked for are not held back by it.
TEST(MapRequestAnswererTest, TheRollingKeyframeKeepsToItsShareOfTheBudgetAskedTilesDoNot) {
  AggregatorNodeOptions options;
  options.keyframe_period_s = 0.5;  // would be every tile twice a second
  options.downlink_bytes_per_s = 2000.0;
  options.keyframe_share = 0.5;      // 1000 B/s
  options.max_message_bytes = 1024;  // the share's burst
  Answering a(options);
  const auto keyframe_bytes = [&a] {
    size_t bytes = 0;
    for (const SentMessage& m : a.parts.out.sent)
      if (m.channel == lcmtypes::kMapKeyframeChannel) bytes += m.bytes.size();
    return bytes;
  };
  for (int tick = 1; tick <= 200; ++tick) a.answerer.Tick(0.1 * tick);  // 20 s
  EXPECT_GT(keyframe_bytes(), 15000u);
  EXPECT_LE(keyframe_bytes(), 1024u + 20 * 1000u + 1000u) << "one message past the share at most";
  EXPECT_LE(a.parts.counters.keyframe_rounds, 4) << "far fewer than the 40 rounds asked for";
  const size_t rolling = a.parts.out.Count(lcmtypes::kMapKeyframeChannel);
  a.Ask(-1);
  a.answerer.Tick(20.05);
  const int32_t count =
      a.parts.out.Decoded<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel)[0].tile_count;
  EXPECT_GE(a.parts.out.Count(lcmtypes::kMapKeyframeChannel), rolling + count);
}

TEST(MapRequestAnswererTest, APeriodOfZeroSendsNoKeyframeUnasked) {
  AggregatorNodeOptions options;
  options.keyframe_period_s = 0.0;
  Answering a(options);
  a.answerer.Tick(1e6);
  EXPECT_TRUE(a.parts.out.sent.empty());
}

}  // namespace
}  // namespace fleetmap::aggregator::node
