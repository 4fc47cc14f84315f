#include "ops/mapctl/map_edits.h"

#include <gtest/gtest.h>

#include "ops/mapctl/merge_summary.h"
#include "tests/ops/mapctl/mapctl_fixture.h"

namespace fleetmap::ops::mapctl {
namespace {

using testing::Cell;
using testing::StoreAt;
using testing::TinyHall;

core::CellState StateOf(const core::OccupancyGrid& g, int64_t cell) {
  return g.state({static_cast<int>(cell % 20), static_cast<int>(cell / 20)});
}

TEST(MergeSummaryTest, CountsKindsAndBoundsTheCellsInMetres) {
  const auto s = Summarize(testing::History()[1], TinyHall().geometry());
  EXPECT_EQ(s.version, 2u);
  EXPECT_EQ(s.vehicle_id, "cts2");
  EXPECT_EQ(s.added, 2);
  EXPECT_EQ(s.candidates, 1);
  EXPECT_EQ(s.removed, 0);
  ASSERT_TRUE(s.has_box);
  // Cells (10, 10) .. (13, 12) at 10 cm from the origin (1, 2): x 2.0 .. 2.4, y 3.0 .. 3.3.
  EXPECT_NEAR(s.box.x0_m, 2.0, 1e-9);
  EXPECT_NEAR(s.box.x1_m, 2.4, 1e-9);
  EXPECT_NEAR(s.box.y0_m, 3.0, 1e-9);
  EXPECT_NEAR(s.box.y1_m, 3.3, 1e-9);
  EXPECT_EQ(FormatSummary(s), "2 200.000 cts2 2 2 0 1 0 2.00 3.00 2.40 3.30");
}

TEST(ResetRegionTest, TheRegionBecomesTheStaticMapAndTheRestStays) {
  auto store = StoreAt(3);  // obstacles at (6, 5), (12, 12), (13, 12); a candidate at (10, 10)
  // A box around cells 9..12 x 9..12 (centres 1.95 .. 2.25 m, 2.95 .. 3.25 m).
  const auto commit = ResetRegionCommit(store, {2.26, 3.26, 1.9, 2.9}, 400.0);
  EXPECT_EQ(commit.version, 4u);
  EXPECT_EQ(commit.source.vehicle_id, kEditVehicleId);
  ASSERT_EQ(commit.changes.size(), 2u);
  EXPECT_EQ(commit.changes[0].cell, Cell(10, 10));
  EXPECT_EQ(commit.changes[0].kind, aggregator::CellChangeKind::kCandidateDropped);
  EXPECT_EQ(commit.changes[1].cell, Cell(12, 12));
  EXPECT_EQ(commit.changes[1].kind, aggregator::CellChangeKind::kRemoved);
  ASSERT_TRUE(store.Apply(commit).ok());
  EXPECT_EQ(StateOf(store.current_map(), Cell(12, 12)), core::CellState::kFree);
  EXPECT_EQ(StateOf(store.current_map(), Cell(13, 12)), core::CellState::kOccupied);
  EXPECT_EQ(StateOf(store.current_map(), Cell(6, 5)), core::CellState::kOccupied);
  EXPECT_EQ(store.candidates().count(Cell(10, 10)), 0u);
}

TEST(PromoteTest, SelectsObstaclesBySinceVersionOrAge) {
  const auto store = StoreAt(3);
  PromoteOptions by_version;
  by_version.since_version = 1;
  EXPECT_EQ(StandingCells(store, by_version), std::vector<int64_t>{Cell(6, 5)});
  PromoteOptions by_age;
  by_age.min_age_s = 150.0;
  by_age.now_s = 360.0;  // added at 100 (260 s ago) and at 200 (160 s ago)
  EXPECT_EQ(StandingCells(store, by_age),
            (std::vector<int64_t>{Cell(6, 5), Cell(12, 12), Cell(13, 12)}));
  by_age.now_s = 300.0;
  EXPECT_EQ(StandingCells(store, by_age), std::vector<int64_t>{Cell(6, 5)});
  EXPECT_FALSE(PromoteOptions{}.Validate().ok());
}

TEST(PromoteTest, TheNewStaticMapAndHistoryGiveTheSameMap) {
  const auto store = StoreAt(3);
  const std::vector<int64_t> cells = {Cell(6, 5)};
  const Promotion p = Promote(store, cells);
  EXPECT_EQ(StateOf(p.static_map, Cell(6, 5)), core::CellState::kOccupied);
  EXPECT_EQ(StateOf(p.static_map, Cell(5, 5)), core::CellState::kFree);
  ASSERT_EQ(p.commits.size(), 3u);
  EXPECT_EQ(p.commits[0].changes.size(), 1u);  // (5, 5) only: (6, 5) is static now
  aggregator::CurrentMapStore rebased(p.static_map, {});
  for (const auto& c : p.commits) ASSERT_TRUE(rebased.Apply(c).ok());
  EXPECT_EQ(rebased.version(), 3u);
  EXPECT_EQ(rebased.current_map().cells(), store.current_map().cells());
  EXPECT_EQ(rebased.semi_static()[static_cast<size_t>(Cell(6, 5))], 0);
  EXPECT_EQ(rebased.semi_static()[static_cast<size_t>(Cell(12, 12))], 1);
}

}  // namespace
}  // namespace fleetmap::ops::mapctl
