// A tiny hall (2 m x 2 m at 10 cm, walls on the border, origin (1, 2)) and a state folder
// written by the aggregator's own persistence, for the mapctl tests.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "aggregator/current_map_store.h"
#include "aggregator/persistence/map_persistence.h"
#include "tests/aggregator/test_files.h"

namespace fleetmap::ops::mapctl::testing {

using aggregator::CellChange;
using aggregator::CellChangeKind;
using aggregator::MergeCommit;

inline core::OccupancyGrid TinyHall() {
  core::OccupancyGrid g(core::GridGeometry(0.1, 20, 20, {1.0, 2.0, 0.0}));
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) {
      const bool wall = x == 0 || y == 0 || x == 19 || y == 19;
      g.SetState({x, y}, wall ? core::CellState::kOccupied : core::CellState::kFree);
    }
  }
  return g;
}

inline int64_t Cell(int x, int y) { return int64_t{y} * 20 + x; }

inline MergeCommit Commit(uint64_t version, const std::string& vehicle, double merged_s,
                          std::vector<CellChange> changes) {
  MergeCommit c;
  c.version = version;
  c.source = {vehicle, static_cast<int32_t>(version), merged_s - 5.0, merged_s - 1.0, merged_s};
  c.changes = std::move(changes);
  return c;
}

// Version 1: a pallet at cells (5..6, 5) by cts1 at t=100; 2: a candidate at (10, 10) and
// another pallet at (12..13, 12) by cts2 at t=200; 3: the first pallet gone, (5, 5) only,
// by cts1 at t=300.
inline std::vector<MergeCommit> History() {
  return {Commit(1, "cts1", 100,
                 {{Cell(5, 5), CellChangeKind::kAdded}, {Cell(6, 5), CellChangeKind::kAdded}}),
          Commit(2, "cts2", 200,
                 {{Cell(10, 10), CellChangeKind::kCandidate},
                  {Cell(12, 12), CellChangeKind::kAdded},
                  {Cell(13, 12), CellChangeKind::kAdded}}),
          Commit(3, "cts1", 300, {{Cell(5, 5), CellChangeKind::kRemoved}})};
}

// The store after the first `n` commits of History().
inline aggregator::CurrentMapStore StoreAt(size_t n) {
  aggregator::CurrentMapStore store(TinyHall(), {});
  const auto commits = History();
  for (size_t i = 0; i < n; ++i) EXPECT_TRUE(store.Apply(commits[i]).ok());
  return store;
}

// Writes History() into `folder` as the aggregator does: a snapshot after `snapshot_after`
// commits, the rest in the journal.
inline void WriteState(const std::string& folder, size_t snapshot_after) {
  aggregator::CurrentMapStore store(TinyHall(), {});
  auto persistence = aggregator::MapPersistence::Open(folder, store, {});
  ASSERT_TRUE(persistence.ok()) << persistence.status().ToString();
  const auto commits = History();
  for (size_t i = 0; i < commits.size(); ++i) {
    ASSERT_TRUE(persistence->Record(commits[i]).ok());
    ASSERT_TRUE(store.Apply(commits[i]).ok());
    if (i + 1 == snapshot_after) {
      ASSERT_TRUE(persistence->Snapshot(store).ok());
    }
  }
}

}  // namespace fleetmap::ops::mapctl::testing
