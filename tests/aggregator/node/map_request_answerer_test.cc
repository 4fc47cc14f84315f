// Catching vehicles up (map_request_answerer.h), driven directly with MAP_REQUEST payloads:
// deltas from a retained version, coalesced keyframes of the tiles asked for, impossible
// requests refused, and the periodic keyframe answering what waits.
#include "aggregator/node/map_request_answerer.h"

#include <gtest/gtest.h>

#include <set>

#include "tests/aggregator/node/node_parts_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::KeyOf;
using testing::NodeParts;
using testing::PalletMaps;
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
  EXPECT_EQ(a.parts.counters.keyframes_sent, 0);
}

TEST(MapRequestAnswererTest, KeyframeRequestsAreCoalescedAndAtMostOncePerInterval) {
  Answering a;
  a.Ask(0, {5});
  a.Ask(0, {1, 5});
  a.answerer.Tick(1.0);
  EXPECT_EQ(a.KeyframeTiles(), (std::vector<int32_t>{1, 5}));
  EXPECT_EQ(a.parts.counters.keyframes_sent, 1);
  a.Ask(4);  // a vehicle ahead of us (our state was lost): the whole map
  a.answerer.Tick(1.2);
  EXPECT_EQ(a.parts.counters.keyframes_sent, 1);  // keyframe_min_interval_s not yet passed
  EXPECT_TRUE(a.answerer.keyframe_waiting());
  a.answerer.Tick(1.5);
  EXPECT_EQ(a.parts.counters.keyframes_sent, 2);
  EXPECT_GT(a.KeyframeTiles().size(), 3u);
  EXPECT_FALSE(a.answerer.keyframe_waiting());
}

TEST(MapRequestAnswererTest, ARequestTheMapCannotAnswerIsRefusedCountedAndLoggedOnce) {
  Answering a;
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

TEST(MapRequestAnswererTest, ThePeriodicKeyframeGoesOutWithTheCandidatesAndAnswersWhatWaits) {
  AggregatorNodeOptions options;
  options.keyframe_period_s = 10.0;
  Answering a(options);
  a.answerer.Tick(9.9);
  EXPECT_TRUE(a.parts.out.sent.empty());
  a.Ask(0, {3});
  a.answerer.Tick(10.0);
  EXPECT_EQ(a.parts.counters.keyframes_sent, 1);  // the whole one; the request needs no other
  EXPECT_EQ(a.parts.counters.candidate_sets_sent, 1);
  EXPECT_FALSE(a.answerer.keyframe_waiting());
  a.answerer.Tick(19.9);
  EXPECT_EQ(a.parts.counters.keyframes_sent, 1);
  a.answerer.Tick(20.0);
  EXPECT_EQ(a.parts.counters.keyframes_sent, 2);
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
