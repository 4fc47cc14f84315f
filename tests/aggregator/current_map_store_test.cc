#include "aggregator/current_map_store.h"

#include <gtest/gtest.h>

#include "aggregator/merge_commit.h"

namespace fleetmap::aggregator {
namespace {

// 200 x 100 cells, free, a wall on row 0: 4 x 2 tiles of 64 cells (edge tiles clipped).
core::OccupancyGrid Map() {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 200, 100));
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x)
      grid.SetState({x, y}, y == 0 ? core::CellState::kOccupied : core::CellState::kFree);
  return grid;
}

MergeCommit Commit(uint64_t version, std::vector<CellChange> changes, int32_t seq = 1) {
  return {version, {"v1", seq, 1.0 * seq, 2.0 * seq, 3.0 * seq}, {}, std::move(changes)};
}

TEST(CurrentMapStoreTest, VersionsTilesAndDeltasFollowEachMerge) {
  CurrentMapStore store(Map(), {});
  EXPECT_EQ(store.version(), 0u);
  const core::OccupancyGrid v0 = store.current_map();
  // Cell (10, 10) lies in tile (0, 0), cell (150, 70) in tile (2, 1).
  auto d1 = store.Apply(Commit(
      1, {{10 * 200 + 10, CellChangeKind::kAdded}, {70 * 200 + 150, CellChangeKind::kAdded}}));
  ASSERT_TRUE(d1.ok()) << d1.status().ToString();
  EXPECT_EQ(store.version(), 1u);
  EXPECT_EQ(d1->from_version, 0u);
  EXPECT_EQ(d1->tiles.size(), 2u);
  EXPECT_EQ(store.TileVersion({0, 0}), 1u);
  EXPECT_EQ(store.TileVersion({2, 1}), 1u);
  EXPECT_EQ(store.TileVersion({1, 0}), 0u);
  EXPECT_EQ(store.current_map().state({10, 10}), core::CellState::kOccupied);
  const core::OccupancyGrid v1 = store.current_map();
  ASSERT_TRUE(store.Apply(Commit(2, {{10 * 200 + 10, CellChangeKind::kRemoved}}, 2)).ok());
  EXPECT_EQ(store.current_map().log_odds({10, 10}), v0.log_odds({10, 10}));  // back to static
  EXPECT_EQ(store.current_map().state({150, 70}), core::CellState::kOccupied);

  // A vehicle at version 0 applies the deltas in order and has the same map.
  core::OccupancyGrid vehicle = v0;
  ASSERT_TRUE(core::ApplyTiles(store.Delta(0).value().tiles, 64, vehicle).ok());
  EXPECT_EQ(vehicle.cells(), v1.cells());
  ASSERT_TRUE(core::ApplyTiles(store.Delta(1).value().tiles, 64, vehicle).ok());
  EXPECT_EQ(vehicle.cells(), store.current_map().cells());
  EXPECT_EQ(store.Delta(2).status().code(), core::StatusCode::kNotFound);
  // One that missed versions catches up from the tile versions, one that has nothing from a
  // keyframe.
  core::OccupancyGrid late = v0;
  const MapDelta since = store.DeltaSince(0);
  EXPECT_EQ(since.tiles.size(), 2u);
  ASSERT_TRUE(core::ApplyTiles(since.tiles, 64, late).ok());
  EXPECT_EQ(late.cells(), store.current_map().cells());
  core::OccupancyGrid blank(store.current_map().geometry());
  const MapDelta keyframe = store.Keyframe();
  EXPECT_EQ(keyframe.tiles.size(), 8u);
  ASSERT_TRUE(core::ApplyTiles(keyframe.tiles, 64, blank).ok());
  EXPECT_EQ(blank.cells(), store.current_map().cells());
}

TEST(CurrentMapStoreTest, RefusesCommitsThatDoNotFitAndChangesNothing) {
  CurrentMapStore store(Map(), {});
  ASSERT_TRUE(store.Apply(Commit(1, {{500, CellChangeKind::kAdded}})).ok());
  const std::vector<float> before = store.current_map().cells();
  const std::vector<MergeCommit> bad = {
      Commit(3, {{600, CellChangeKind::kAdded}}),             // a version gap
      Commit(2, {{10, CellChangeKind::kAdded}}),              // a static (wall) cell
      Commit(2, {{500, CellChangeKind::kAdded}}),             // already there
      Commit(2, {{700, CellChangeKind::kRemoved}}),           // nothing to remove
      Commit(2, {{900, CellChangeKind::kCandidateDropped}}),  // no such candidate
      Commit(2, {{20000, CellChangeKind::kAdded}}),           // outside the map
      Commit(2, {{800, CellChangeKind::kAdded}, {700, CellChangeKind::kAdded}}),  // order
      Commit(2, {{800, CellChangeKind::kAdded}, {10, CellChangeKind::kAdded}}),   // half good
  };
  for (const MergeCommit& c : bad) {
    EXPECT_EQ(store.Apply(c).status().code(), core::StatusCode::kFailedPrecondition);
    EXPECT_EQ(store.version(), 1u);
    EXPECT_EQ(store.current_map().cells(), before);
  }
  EXPECT_EQ(store.provenance().commits().size(), 1u);
}

TEST(CurrentMapStoreTest, CandidatesLeaveTheMapAlone) {
  CurrentMapStore store(Map(), {});
  auto delta = store.Apply(Commit(1, {{500, CellChangeKind::kCandidate}}));
  ASSERT_TRUE(delta.ok());
  EXPECT_TRUE(delta->tiles.empty());
  EXPECT_EQ(store.version(), 1u);  // an accepted merge, even without a visible change
  EXPECT_EQ(store.candidates().count(500), 1u);
  EXPECT_EQ(store.candidates().at(500).first.start_s, 1.0);
  EXPECT_EQ(store.current_map().cells(), Map().cells());
}

TEST(CurrentMapStoreTest, AWatchedCandidateKeepsItsFirstSightingAndWhenLastSeen) {
  CurrentMapStore store(Map(), {});
  EXPECT_EQ(store.Apply(Commit(1, {{500, CellChangeKind::kCandidateWatched}})).status().code(),
            core::StatusCode::kFailedPrecondition);  // no candidate there
  ASSERT_TRUE(store.Apply(Commit(1, {{500, CellChangeKind::kCandidate}})).ok());
  EXPECT_EQ(store.candidates().at(500).first.end_s, 2.0);  // where its watch starts
  ASSERT_TRUE(store.Apply(Commit(2, {{500, CellChangeKind::kCandidateWatched}}, 2)).ok());
  const Candidate& c = store.candidates().at(500);
  EXPECT_EQ(c.first.start_s, 1.0);
  EXPECT_EQ(c.first.end_s, 2.0);
  EXPECT_EQ(c.last_seen_end_s, 4.0);
  EXPECT_EQ(store.current_map().cells(), Map().cells());
}

TEST(CurrentMapStoreTest, ACandidateSeenAgainIsRenewedButNoObstacleIs) {
  CurrentMapStore store(Map(), {});
  ASSERT_TRUE(store.Apply(Commit(1, {{500, CellChangeKind::kCandidate}})).ok());
  ASSERT_TRUE(store.Apply(Commit(2, {{500, CellChangeKind::kCandidate}}, 2)).ok());
  EXPECT_EQ(store.candidates().at(500).first.start_s, 2.0);  // the later map's span
  EXPECT_EQ(store.candidates().at(500).first.end_s, 4.0);
  ASSERT_TRUE(store.Apply(Commit(3, {{600, CellChangeKind::kAdded}}, 3)).ok());
  EXPECT_EQ(store.Apply(Commit(4, {{600, CellChangeKind::kCandidate}}, 4)).status().code(),
            core::StatusCode::kFailedPrecondition);
}

TEST(MergeCommitTest, RoundTripAndCorruption) {
  const MergeCommit c = Commit(7, {{3, CellChangeKind::kAdded}, {9, CellChangeKind::kCandidate}});
  const std::vector<uint8_t> bytes = EncodeCommit(c);
  auto back = DecodeCommit(bytes.data(), bytes.size());
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->version, 7u);
  EXPECT_EQ(back->source.vehicle_id, "v1");
  EXPECT_EQ(back->source.merged_s, 3.0);
  EXPECT_EQ(back->changes, c.changes);
  for (size_t n = 0; n < bytes.size(); ++n)
    EXPECT_FALSE(DecodeCommit(bytes.data(), n).ok()) << n;  // every truncation
  std::vector<uint8_t> bad = bytes;
  bad.back() = 9;  // an unknown change kind
  EXPECT_EQ(DecodeCommit(bad.data(), bad.size()).status().code(), core::StatusCode::kDataLoss);
  bad = bytes;
  bad[0] = kCommitFormatVersion + 1;
  EXPECT_EQ(DecodeCommit(bad.data(), bad.size()).status().code(), core::StatusCode::kUnimplemented);
}

TEST(ProvenanceTest, AnswersWhatChangedWhereWhenSeenByWhom) {
  ProvenanceLog log;
  log.Record(Commit(1, {{5, CellChangeKind::kAdded}, {6, CellChangeKind::kAdded}}, 1));
  MergeCommit other = Commit(2, {{5, CellChangeKind::kRemoved}}, 2);
  other.source.vehicle_id = "v2";
  log.Record(other);
  const auto history = log.HistoryOf(5);
  ASSERT_EQ(history.size(), 2u);
  EXPECT_EQ(history[0].kind, CellChangeKind::kAdded);
  EXPECT_EQ(history[0].source->vehicle_id, "v1");
  EXPECT_EQ(history[1].version, 2u);
  EXPECT_EQ(history[1].source->vehicle_id, "v2");
  EXPECT_EQ(log.ChangesBetween(0.0, 3.5).size(), 2u);  // merged at 3 s
  EXPECT_EQ(log.ChangesSeenBy("v2").size(), 1u);
  EXPECT_TRUE(log.HistoryOf(99).empty());
  EXPECT_EQ(log.num_changes(), 3u);
}

}  // namespace
}  // namespace fleetmap::aggregator
