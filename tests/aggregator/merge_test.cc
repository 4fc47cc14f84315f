// What a merge leaves alone and what it removes: older evidence against a newer change,
// static cells and their clearance, isolated returns, a removal's neighbourhood and the hits
// that keep cells, maps that draw the walls off; and a pallet removed from the hall.
#include "aggregator/merge.h"

#include <gtest/gtest.h>

#include <vector>

#include "aggregator/aggregator.h"
#include "aggregator/current_map_store.h"
#include "tests/aggregator/merge_fixture.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

using testing::Evidence;
using testing::kFree;
using testing::kHit;
using testing::MergeTest;
using testing::Set;

// Maps merge in the order they complete, not the order they were made (a lossy link, a
// vehicle back in range): older evidence does not undo a newer change.
TEST_F(MergeTest, AMapOlderThanACellsLastChangeLeavesIt) {
  options_.confirm_min_gap_s = 2.0;  // a timeline of short gaps
  PlacedEvidence hit = Evidence(), free = Evidence();
  Set(hit, 8, 8, 10, 10, kHit);
  Set(free, 4, 4, 14, 14, kFree);
  Commit(Plan(hit, {10, 13}), {10, 13});  // a pallet put down at 9 s, seen twice
  Commit(Plan(hit, {16, 19}), {16, 19});
  ASSERT_EQ(Semi(), 9);
  EXPECT_EQ(Plan(free, {0, 3}).removed, 0);      // seen free before it was put down
  EXPECT_EQ(Plan(free, {14, 17}).removed, 0);    // ended before the map that added it
  const MergePlan taken = Plan(free, {30, 33});  // taken away later
  EXPECT_EQ(taken.removed, 9);
  Commit(taken, {30, 33});
  ASSERT_EQ(Semi(), 0);
  // Sightings from before the removal do not bring it back (at first sight, to show it).
  options_.confirmations = 1;
  EXPECT_EQ(Plan(hit, {22, 25}).added, 0);
  EXPECT_EQ(Plan(hit, {34, 37}).added, 9);
  options_.confirmations = 2;
  // A candidate seen at 40 s is not dropped by a map of 35 s that saw the place free.
  Set(hit, 8, 8, 10, 10, kHit);
  Commit(Plan(hit, {38, 41}), {38, 41});
  ASSERT_EQ(store_.candidates().size(), 9u);
  EXPECT_EQ(Plan(free, {32, 35}).dropped, 0);
  EXPECT_EQ(Plan(free, {42, 45}).dropped, 9);
}

TEST_F(MergeTest, StaticCellsNeverChangeAndTheirSurroundingsAreNotAdded) {
  options_.confirmations = 1;
  PlacedEvidence e = Evidence();
  Set(e, 0, 0, 19, 3, kHit);  // the wall row and the rows in front of it, all "occupied"
  Set(e, 0, 5, 19, 19, kFree);
  const MergePlan plan = Plan(e, {0, 10});
  ASSERT_EQ(plan.added, 20);  // only row 3: rows 1 and 2 lie within the clearance
  for (const CellChange& c : plan.changes) EXPECT_EQ(c.cell / 20, 3);
}

TEST_F(MergeTest, AnIsolatedReturnIsNoObstacle) {
  options_.confirmations = 1;
  PlacedEvidence e = Evidence();
  Set(e, 10, 10, 10, 10, kHit);
  EXPECT_EQ(Plan(e, {0, 10}).added, 0);
  Set(e, 11, 10, 11, 10, kHit);
  EXPECT_EQ(Plan(e, {0, 10}).added, 2);
}

TEST_F(MergeTest, RemovalNeedsTheWholeNeighbourhoodSeenFree) {
  options_.confirmations = 1;
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 11, 10, kHit);
  Commit(Plan(e, {0, 10}), {0, 10});
  ASSERT_EQ(Semi(), 12);
  // A strip seen free while the rest of the obstacle is unobserved: kept.
  e = Evidence();
  Set(e, 8, 10, 11, 11, kFree);
  EXPECT_EQ(Plan(e, {20, 30}).removed, 0);
  // The whole obstacle seen free: removed.
  Set(e, 7, 7, 12, 11, kFree);
  const MergePlan gone = Plan(e, {20, 30});
  EXPECT_EQ(gone.removed, 12);
  // Free but one cell still hit next to it: the cells around the hit stay.
  Set(e, 8, 8, 8, 8, kHit);
  EXPECT_LT(Plan(e, {20, 30}).removed, 12);
}

// An obstacle still there flickers at its edge: a hit two cells from a semi-static cell keeps
// it (removal_clearance_m = 0.10 m, 2 cells at 5 cm); with a clearance of one cell it would
// be removed.
TEST_F(MergeTest, RemovalKeepsCellsWithinTheClearanceOfAHit) {
  options_.confirmations = 1;
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 11, 10, kHit);
  Commit(Plan(e, {0, 10}), {0, 10});
  ASSERT_EQ(Semi(), 12);
  e = Evidence();
  Set(e, 6, 6, 15, 12, kFree);
  Set(e, 13, 9, 13, 9, kHit);  // an isolated return two cells east of column 11
  const MergePlan kept = Plan(e, {20, 30});
  EXPECT_EQ(kept.removed, 9);  // columns 8-10 go, column 11 stays
  for (const CellChange& c : kept.changes) EXPECT_LT(c.cell % 20, 11) << c.cell;
  options_.removal_clearance_m = 0.05;
  EXPECT_EQ(Plan(e, {20, 30}).removed, 12);
}

// The same distance in metres is the same number of cells' worth at every resolution.
// A map placed 0.15 m off draws the wall it saw as a second wall in front of it, farther
// than static_clearance_m (0.10 m): its own hits near walls say how far off it is, and it adds
// nothing that close to a wall. A pallet in the open is still added.
TEST_F(MergeTest, AMapThatDrawsTheWallsOffAddsNothingThatCloseToThem) {
  options_.confirmations = 1;
  const std::vector<uint8_t> walls = WallDistances(store_.static_map(), options_.thresholds);
  PlacedEvidence e = Evidence();
  Set(e, 0, 3, 19, 3, kHit);  // the wall of row 0, drawn 3 cells (0.15 m) in front of it
  Set(e, 8, 10, 10, 12, kHit);
  EXPECT_EQ(Plan(e, {0, 3}).added, 20 + 9);  // without the guard the second wall is added
  wall_distance_ = &walls;
  const MergePlan plan = Plan(e, {0, 3});
  EXPECT_EQ(plan.added, 9);
  EXPECT_EQ(plan.dirty, (core::CellWindow{8, 10, 3, 3}));
  options_.wall_offset_window_m = 0;  // switched off
  EXPECT_EQ(Plan(e, {0, 3}).added, 20 + 9);
}

// A map that draws the wall where it is keeps the static clearance: a box 0.15 m in front of
// the wall is added.
TEST_F(MergeTest, AMapThatDrawsTheWallsInPlaceAddsWhatIsNearThem) {
  options_.confirmations = 1;
  const std::vector<uint8_t> walls = WallDistances(store_.static_map(), options_.thresholds);
  wall_distance_ = &walls;
  PlacedEvidence e = Evidence();
  Set(e, 0, 0, 19, 1, kHit);  // the wall and its face: 40 hits at 0 and 1 cell
  Set(e, 8, 3, 10, 3, kHit);  // the box's face, 3 cells from the wall
  EXPECT_EQ(Plan(e, {0, 3}).added, 3);
}

// The required behaviour: a removal clears the pallet but not the wall behind it.
TEST(MergeHallTest, RemovalClearsThePalletButNotTheWallBehindIt) {
  using testing::BuildTempMap;
  const core::OccupancyGrid hall = testing::HallMap();
  // A pallet 0.4 m in front of the north wall (whose face is at y = 19.85).
  const testing::Box pallet{{15.0, 19.05}, {1.2, 0.8}};
  const core::OccupancyGrid with_pallet = testing::HallMap(0.0, {pallet});
  auto aggregator = Aggregator::Create(hall, {});
  ASSERT_TRUE(aggregator.ok());
  testing::TempMapSpec spec;
  spec.start = {13.013, 16.027, 0.0};
  spec.anchor_error = {0.1, -0.08, 1.0 * M_PI / 180};
  spec.start_s = 0, spec.end_s = 10, spec.sequence = 1;
  ASSERT_TRUE(aggregator->Submit(BuildTempMap(with_pallet, spec), 10).value().accepted);
  spec.start_s = 20, spec.end_s = 30, spec.sequence = 2, spec.seed = 8;
  spec.anchor_error = {-0.12, 0.1, -1.5 * M_PI / 180};
  const MergeReport seen = aggregator->Submit(BuildTempMap(with_pallet, spec), 30).value();
  ASSERT_TRUE(seen.accepted) << seen.reason_text;
  EXPECT_GT(seen.cells_added, 40);  // the pallet's faces the vehicle saw
  const core::GridGeometry& g = hall.geometry();
  const int64_t pallet_face = g.Index(g.WorldToCell({15.0, 18.63}));
  ASSERT_TRUE(aggregator->store().semi_static()[pallet_face]);

  spec.start_s = 40, spec.end_s = 50, spec.sequence = 3, spec.seed = 9;
  spec.anchor_error = {0.05, 0.15, 2.0 * M_PI / 180};
  const MergeReport gone = aggregator->Submit(BuildTempMap(hall, spec), 50).value();
  ASSERT_TRUE(gone.accepted) << gone.reason_text;
  EXPECT_GT(gone.cells_removed, 40);
  // No obstacle left near the pallet, and every static cell as it was.
  for (int y = g.WorldToCell({0, 18.0}).y; y < g.height(); ++y) {
    for (int x = g.WorldToCell({13.5, 0}).x; x <= g.WorldToCell({16.5, 0}).x; ++x) {
      EXPECT_FALSE(aggregator->store().semi_static()[g.Index({x, y})]) << x << ", " << y;
      EXPECT_EQ(aggregator->store().current_map().log_odds({x, y}), hall.log_odds({x, y}));
    }
  }
  EXPECT_EQ(aggregator->store().current_map().cells(), hall.cells());
  // The history answers what changed where, when, seen by whom.
  const auto history = aggregator->store().provenance().HistoryOf(pallet_face);
  ASSERT_GE(history.size(), 2u);
  EXPECT_EQ(history.front().kind, CellChangeKind::kCandidate);
  EXPECT_EQ(history.back().kind, CellChangeKind::kRemoved);
  EXPECT_EQ(history.back().source->vehicle_id, "v1");
  EXPECT_EQ(history.back().source->tempmap_sequence, 3);
  EXPECT_EQ(history.back().source->merged_s, 50.0);
  EXPECT_EQ(history.back().version, aggregator->store().version());
}

}  // namespace
}  // namespace fleetmap::aggregator
