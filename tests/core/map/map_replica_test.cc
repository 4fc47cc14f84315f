#include "core/map/map_replica.h"

#include <gtest/gtest.h>

#include "tests/core/map/keyframe_tiles.h"

namespace fleetmap::core {
namespace {

OccupancyGrid Hall() {
  OccupancyGrid g(GridGeometry(0.05, 150, 100, Pose2(1, 2, 0)));
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 150; ++x)
      g.SetState({x, y}, x == 0 || y == 0 ? CellState::kOccupied : CellState::kFree);
  return g;
}

using testing::Keyframe;

std::vector<DeltaTile> Delta(const OccupancyGrid& a, const OccupancyGrid& b, int32_t base) {
  std::vector<DeltaTile> out;
  const auto tiles = EncodeChangedTiles(a, b);
  for (size_t i = 0; i < tiles.size(); ++i)
    out.push_back({base, int32_t(i), int32_t(tiles.size()), tiles[i].index, tiles[i].frame});
  if (tiles.empty()) out.push_back({base, 0, 0, {}, {}});
  return out;
}

OccupancyGrid WithPallet(OccupancyGrid g, int x0) {
  for (int y = 50; y < 60; ++y)
    for (int x = x0; x < x0 + 10; ++x) g.SetState({x, y}, CellState::kOccupied);
  return g;
}

bool SameStates(const OccupancyGrid& a, const OccupancyGrid& b) {
  const TriStateClassifier c;
  for (size_t i = 0; i < a.cells().size(); ++i)
    if (c(a.cells()[i]) != c(b.cells()[i])) return false;
  return true;
}

TEST(MapReplicaTest, KeyframeThenDeltasInOrder) {
  const OccupancyGrid v3 = Hall(), v4 = WithPallet(v3, 20), v5 = WithPallet(v4, 100);
  MapReplica replica;
  EXPECT_TRUE(replica.NeedsKeyframe());
  const auto key = Keyframe(v3, 3);
  for (size_t i = 0; i < key.size(); ++i) {
    auto r = replica.AddKeyframeTile(key[i]);
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    EXPECT_EQ(*r, i + 1 == key.size());
  }
  EXPECT_EQ(replica.version(), 3);
  for (const DeltaTile& t : Delta(v3, v4, 3)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  EXPECT_EQ(replica.version(), 4);
  EXPECT_TRUE(SameStates(replica.map(), v4));
  for (const DeltaTile& t : Delta(v4, v5, 4)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  EXPECT_EQ(replica.version(), 5);
  EXPECT_TRUE(SameStates(replica.map(), v5));
  EXPECT_FALSE(replica.NeedsKeyframe());
}

// What a vehicle's scan models must recompute: everything after a keyframe, the tiles of the
// deltas applied since (pallets at x 20 and 100 of a 150 x 100 grid cut into 64-cell tiles:
// tiles (0, 0) and (1, 0)), nothing when nothing changed.
TEST(MapReplicaTest, SaysWhereTheMapChangedSinceItWasLastAsked) {
  const OccupancyGrid v1 = Hall(), v2 = WithPallet(v1, 20), v3 = WithPallet(v2, 100);
  MapReplica replica;
  EXPECT_EQ(replica.TakeChanged(), CellWindow{}) << "no map";
  for (const auto& t : Keyframe(v1, 1)) ASSERT_TRUE(replica.AddKeyframeTile(t).ok());
  EXPECT_EQ(replica.TakeChanged(), v1.geometry().full_window());
  EXPECT_EQ(replica.TakeChanged(), CellWindow{});
  for (const auto& t : Delta(v1, v2, 1)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  EXPECT_EQ(replica.TakeChanged(), (CellWindow{0, 0, 64, 64}));
  for (const auto& t : Delta(v2, v1, 2)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  for (const auto& t : Delta(v1, v3, 3)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  EXPECT_EQ(replica.version(), 4);
  EXPECT_EQ(replica.TakeChanged(), (CellWindow{0, 0, 128, 64})) << "both versions' tiles";
  ASSERT_TRUE(replica.AddDeltaTile({4, 0, 0, {}, {}}).ok());
  EXPECT_EQ(replica.version(), 5);
  EXPECT_EQ(replica.TakeChanged(), CellWindow{});
  ASSERT_TRUE(replica.Seed(v3, 9).ok());
  EXPECT_EQ(replica.TakeChanged(), v3.geometry().full_window());
}

// The aggregator sends its keyframe tile by tile over seconds: a version can change between
// the first tiles and the last. Tiles of the older version count once the delta between is
// held, the delta's copy replacing a tile it changed (tile 0 here).
TEST(MapReplicaTest, AKeyframeSentAcrossAVersionChangeBuildsTheNewerMap) {
  const OccupancyGrid v1 = Hall(), v2 = WithPallet(v1, 20);
  const auto old_tiles = Keyframe(v1, 1), new_tiles = Keyframe(v2, 2);
  ASSERT_EQ(old_tiles.size(), 6u);
  MapReplica replica;
  EXPECT_TRUE(replica.MissingKeyframeTiles().empty()) << "nothing received: the whole map";
  for (size_t i = 0; i < 3; ++i) ASSERT_TRUE(replica.AddKeyframeTile(old_tiles[i]).ok());
  EXPECT_EQ(replica.MissingKeyframeTiles(), (std::vector<int32_t>{3, 4, 5}));
  for (const DeltaTile& t : Delta(v1, v2, 1)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  for (size_t i = 3; i < 6; ++i) {
    auto r = replica.AddKeyframeTile(new_tiles[i]);
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    EXPECT_EQ(*r, i == 5);
  }
  EXPECT_EQ(replica.version(), 2);
  EXPECT_TRUE(SameStates(replica.map(), v2)) << "tile 0 as the delta changed it";
  EXPECT_FALSE(replica.NeedsKeyframe());
}

// Without the delta between, the older tiles cannot be trusted: they are dropped, asked for
// again, and the map is built from their next copies.
TEST(MapReplicaTest, KeyframeTilesOlderThanAMissedDeltaWaitForTheirNextCopy) {
  const OccupancyGrid v1 = Hall(), v2 = WithPallet(v1, 20);
  const auto old_tiles = Keyframe(v1, 1), new_tiles = Keyframe(v2, 2);
  MapReplica replica;
  for (size_t i = 0; i < 3; ++i) ASSERT_TRUE(replica.AddKeyframeTile(old_tiles[i]).ok());
  for (size_t i = 3; i < 6; ++i) ASSERT_TRUE(replica.AddKeyframeTile(new_tiles[i]).ok());
  EXPECT_FALSE(replica.has_map());
  EXPECT_EQ(replica.MissingKeyframeTiles(), (std::vector<int32_t>{0, 1, 2}));
  for (size_t i = 0; i < 3; ++i) ASSERT_TRUE(replica.AddKeyframeTile(new_tiles[i]).ok());
  ASSERT_TRUE(replica.has_map());
  EXPECT_EQ(replica.version(), 2);
  EXPECT_TRUE(SameStates(replica.map(), v2));
}

// A delta whose last tile comes after the keyframe's last tile completes the keyframe.
TEST(MapReplicaTest, TheDeltaAKeyframeWaitedForCompletesIt) {
  const OccupancyGrid v1 = Hall(), v2 = WithPallet(WithPallet(v1, 20), 100);
  const auto old_tiles = Keyframe(v1, 1), new_tiles = Keyframe(v2, 2);
  const auto delta = Delta(v1, v2, 1);
  ASSERT_EQ(delta.size(), 2u);
  MapReplica replica;
  for (size_t i = 0; i < 3; ++i) ASSERT_TRUE(replica.AddKeyframeTile(old_tiles[i]).ok());
  ASSERT_TRUE(replica.AddDeltaTile(delta[0]).ok());
  for (size_t i = 3; i < 6; ++i) ASSERT_TRUE(replica.AddKeyframeTile(new_tiles[i]).ok());
  EXPECT_FALSE(replica.has_map()) << "the delta's second tile still to come";
  auto r = replica.AddDeltaTile(delta[1]);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_TRUE(*r);
  EXPECT_EQ(replica.version(), 2);
  EXPECT_TRUE(SameStates(replica.map(), v2));
}

TEST(MapReplicaTest, OutOfOrderDeltasWaitAndAGapAsksForAKeyframe) {
  const OccupancyGrid v1 = Hall(), v2 = WithPallet(v1, 20), v3 = WithPallet(v2, 100);
  MapReplica replica;
  for (const auto& t : Keyframe(v1, 1)) ASSERT_TRUE(replica.AddKeyframeTile(t).ok());
  for (const auto& t : Delta(v2, v3, 2)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  EXPECT_EQ(replica.version(), 1);       // 2 -> 3 waits for 1 -> 2
  EXPECT_TRUE(replica.NeedsKeyframe());  // a version was missed (so far)
  for (const auto& t : Delta(v1, v2, 1)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  EXPECT_EQ(replica.version(), 3);  // both applied, in order
  EXPECT_TRUE(SameStates(replica.map(), v3));
}

TEST(MapReplicaTest, EmptyDeltaAdvancesTheVersion) {
  const OccupancyGrid v1 = Hall();
  MapReplica replica;
  for (const auto& t : Keyframe(v1, 1)) ASSERT_TRUE(replica.AddKeyframeTile(t).ok());
  ASSERT_TRUE(replica.AddDeltaTile({1, 0, 0, {}, {}}).ok());
  EXPECT_EQ(replica.version(), 2);
}

TEST(MapReplicaTest, CorruptTilesAreRefusedAndNothingIsHalfApplied) {
  const OccupancyGrid v1 = Hall(), v2 = WithPallet(v1, 20);
  MapReplica replica;
  auto key = Keyframe(v1, 1);
  key[1].index = 99;
  EXPECT_FALSE(replica.AddKeyframeTile(key[1]).ok());
  key = Keyframe(v1, 1);
  for (const auto& t : key) ASSERT_TRUE(replica.AddKeyframeTile(t).ok());
  auto delta = Delta(v1, v2, 1);
  ASSERT_FALSE(delta.empty());
  delta[0].frame[40] ^= 0xFF;
  for (const auto& t : delta) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  // The corrupt version was not applied; the replica asks for a keyframe instead.
  EXPECT_TRUE(replica.NeedsKeyframe());
  for (const auto& t : Keyframe(v2, 2)) ASSERT_TRUE(replica.AddKeyframeTile(t).ok());
  EXPECT_EQ(replica.version(), 2);
  EXPECT_TRUE(SameStates(replica.map(), v2));
}

TEST(MapReplicaTest, SeededFromAStaticMapAppliesDeltasFromItsVersion) {
  const OccupancyGrid v0 = Hall(), v1 = WithPallet(v0, 20), v2 = WithPallet(v1, 100);
  MapReplica replica;
  EXPECT_FALSE(replica.Seed(v0, -1).ok());
  EXPECT_FALSE(replica.Seed(v0, 0, 2).ok());  // not a usable tiling
  EXPECT_FALSE(replica.has_map());
  // A delta that arrived before the seed waits for it.
  for (const DeltaTile& t : Delta(v1, v2, 1)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  ASSERT_TRUE(replica.Seed(v0, 0).ok());
  EXPECT_EQ(replica.version(), 0);
  EXPECT_TRUE(replica.NeedsKeyframe());  // version 1 is missing
  for (const DeltaTile& t : Delta(v0, v1, 0)) ASSERT_TRUE(replica.AddDeltaTile(t).ok());
  EXPECT_EQ(replica.version(), 2);
  EXPECT_FALSE(replica.NeedsKeyframe());
  EXPECT_TRUE(SameStates(replica.map(), v2));
  // A keyframe of a newer version replaces the seeded map; an older one is old news.
  for (const auto& t : Keyframe(v0, 1)) EXPECT_FALSE(*replica.AddKeyframeTile(t));
  for (const auto& t : Keyframe(v0, 5)) ASSERT_TRUE(replica.AddKeyframeTile(t).ok());
  EXPECT_EQ(replica.version(), 5);
  EXPECT_TRUE(SameStates(replica.map(), v0));
}

}  // namespace
}  // namespace fleetmap::core
