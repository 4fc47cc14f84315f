#include "aggregator/merge.h"

#include <gtest/gtest.h>

#include "aggregator/aggregator.h"
#include "aggregator/candidates_seen_free.h"
#include "aggregator/current_map_store.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

constexpr float kHit = 4.6f, kFree = -4.6f;

// 20 x 20 cells at 5 cm: a wall on row 0, free elsewhere.
core::OccupancyGrid SmallMap() {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 20, 20));
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x)
      grid.SetState({x, y}, y == 0 ? core::CellState::kOccupied : core::CellState::kFree);
  return grid;
}

// Evidence over the whole map, 0 (unobserved) except where set.
PlacedEvidence Evidence() {
  PlacedEvidence e;
  e.map_width = 20;
  e.window = {0, 0, 20, 20};
  e.log_odds.assign(400, 0.0f);
  return e;
}
void Set(PlacedEvidence& e, int x0, int y0, int x1, int y1, float l) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) e.log_odds[size_t(y) * 20 + x] = l;
}

class MergeTest : public ::testing::Test {
 protected:
  MergePlan Plan(const PlacedEvidence& e, TimeSpan span) {
    addable_ = AddableCells(store_.static_map(), options_);
    const MergeInputs in{&addable_,
                         wall_distance_,
                         &store_.semi_static(),
                         &store_.candidates(),
                         &store_.candidate_mask(),
                         &store_.changed_at_s()};
    return PlanMerge(e, span, in, options_);
  }
  void Commit(const MergePlan& plan, TimeSpan span) {
    MergeCommit c{
        store_.version() + 1, {"v1", 1, span.start_s, span.end_s, span.end_s}, {}, plan.changes};
    ASSERT_TRUE(store_.Apply(c).ok());
  }
  int64_t Semi() const {
    return std::count(store_.semi_static().begin(), store_.semi_static().end(), 1);
  }

  MergeOptions options_;
  CurrentMapStore store_{SmallMap(), {}};
  std::vector<uint8_t> addable_;
  const std::vector<uint8_t>* wall_distance_ = nullptr;  // no offset guard unless set
};

TEST_F(MergeTest, FirstSightOnlyWithOneConfirmation) {
  options_.confirmations = 1;
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  const MergePlan plan = Plan(e, {0, 10});
  EXPECT_EQ(plan.added, 9);
  EXPECT_EQ(plan.dirty, (core::CellWindow{8, 8, 3, 3}));
}

TEST_F(MergeTest, AnObstacleNeedsASecondMapOfAnotherTime) {
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  MergePlan first = Plan(e, {0, 3});
  EXPECT_EQ(first.added, 0);
  EXPECT_EQ(first.candidates, 9);
  Commit(first, {0, 3});
  EXPECT_EQ(Semi(), 0);
  EXPECT_EQ(Plan(e, {3, 6}).added, 0);  // touching in time: a person passing by is in both
  const double gap = options_.confirm_min_gap_s;
  const MergePlan later = Plan(e, {3 + gap, 6 + gap});
  EXPECT_EQ(later.added, 9);
  Commit(later, {3 + gap, 6 + gap});
  EXPECT_EQ(Semi(), 9);
  EXPECT_TRUE(store_.candidates().empty());
}

// A forklift stops for a pick and a person waits at a door for seconds: maps a few seconds
// apart both see them standing. The default gap is longer than such a stop.
TEST_F(MergeTest, SomethingStandingForSecondsIsNotConfirmed) {
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  Commit(Plan(e, {0, 3}), {0, 3});
  EXPECT_EQ(Plan(e, {6, 9}).added, 0);  // standing for 9 s, seen by maps 3 s apart
  EXPECT_GE(options_.confirm_min_gap_s, 9.0);
}

// One vehicle passing a new pallet sees it in each of its temporary maps, one after the other,
// for longer than the gap: that watch adds it, without a second pass.
TEST_F(MergeTest, AWatchLongerThanTheGapAddsIt) {
  options_.confirm_by_watch = true;
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  Commit(Plan(e, {0, 3}), {0, 3});
  for (double t = 3; t < 12; t += 3) {  // its watch from 3 s to the map's middle: < 10 s
    const MergePlan more = Plan(e, {t, t + 3});
    EXPECT_EQ(more.added, 0) << t;
    EXPECT_EQ(more.watched, 9) << t;
    Commit(more, {t, t + 3});
  }
  EXPECT_EQ(store_.candidates().at(9 * 20 + 9).last_seen_end_s, 12.0);
  EXPECT_EQ(store_.candidates().at(9 * 20 + 9).first.start_s, 0.0);
  options_.confirm_by_watch = false;
  EXPECT_EQ(Plan(e, {12, 15}).added, 0);  // off: only a map 10 s after the first confirms
  options_.confirm_by_watch = true;
  const MergePlan last = Plan(e, {12, 15});  // 13.5 - 3 >= 10 s
  EXPECT_EQ(last.added, 9);
  Commit(last, {12, 15});
  EXPECT_EQ(Semi(), 9);
}

// A person who stands, walks off and comes back: the maps that saw him are not one after the
// other, and a pause breaks the watch.
TEST_F(MergeTest, AWatchBrokenByAPauseConfirmsNothing) {
  options_.confirm_by_watch = true;
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  Commit(Plan(e, {0, 3}), {0, 3});
  Commit(Plan(e, {3, 6}), {3, 6});
  const PlacedEvidence unseen = Evidence();
  Commit(Plan(unseen, {6, 9}), {6, 9});  // the place not seen: the watch stops at 6 s
  const MergePlan back = Plan(e, {9, 12});
  EXPECT_EQ(back.watched, 0);
  Commit(back, {9, 12});
  EXPECT_EQ(Plan(e, {12, 15}).added, 0);  // 9 s after the first map ended: no confirmation
  options_.watch_join_s = 3.5;  // long enough to join 12 s to 9 s, not to the watch's 6 s:
  EXPECT_EQ(Plan(e, {12, 15}).added, 0);  // the sighting after the pause did not extend it
}

// Cells seen next to an obstacle of the map are another face of it only when this map sees
// the obstacle too: a forklift that stops where a person was wrongly mapped is no face of it.
TEST_F(MergeTest, ANeighbourIsAnotherFaceOnlyWhileTheObstacleIsSeen) {
  PlacedEvidence row = Evidence();
  Set(row, 8, 8, 10, 8, kHit);
  const double gap = options_.confirm_min_gap_s;
  Commit(Plan(row, {0, 3}), {0, 3});
  Commit(Plan(row, {3 + gap, 6 + gap}), {3 + gap, 6 + gap});
  ASSERT_EQ(Semi(), 3);
  PlacedEvidence beside = Evidence();  // the obstacle unobserved, something next to it
  Set(beside, 11, 8, 13, 9, kHit);
  const MergePlan alone = Plan(beside, {6 + gap, 9 + gap});
  EXPECT_EQ(alone.added, 0);
  EXPECT_EQ(alone.candidates, 6);
  Set(beside, 8, 8, 10, 8, kHit);  // the same, with the obstacle seen as well
  EXPECT_EQ(Plan(beside, {6 + gap, 9 + gap}).added, 6);
}

// A person turning at the same place every 25 s: a vehicle passing in between saw the place
// empty, so the next sighting starts a candidate afresh instead of confirming it. A report of
// passes before the last sighting drops nothing.
TEST_F(MergeTest, ACandidateAVehicleSawEmptyIsDroppedAndNotConfirmedLater) {
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  Commit(Plan(e, {0, 3}), {0, 3});
  ASSERT_EQ(store_.candidates().size(), 9u);
  const int64_t centre = 9 * 20 + 9;
  EXPECT_TRUE(PlanCandidateDrops({{centre}, 2.0, 2.5}, store_.candidates()).empty());
  SeenFreeReport report{{centre, 5 * 20 + 5}, 12.0, 12.5};  // and a cell that is no candidate
  for (int y = 8; y <= 10; ++y)
    for (int x = 8; x <= 10; ++x) report.cells.push_back(y * 20 + x);
  const std::vector<CellChange> drops = PlanCandidateDrops(report, store_.candidates());
  ASSERT_EQ(drops.size(), 9u);  // each cell once, only candidates, ascending
  EXPECT_EQ(drops[0], (CellChange{8 * 20 + 8, CellChangeKind::kCandidateDropped}));
  MergeCommit c{store_.version() + 1, {"v2", kSeenFreeSequence, 12.0, 12.5, 13.0}, {}, drops};
  ASSERT_TRUE(store_.Apply(c).ok());
  EXPECT_TRUE(store_.candidates().empty());
  const double gap = options_.confirm_min_gap_s;
  const MergePlan later = Plan(e, {3 + gap, 6 + gap});  // would have confirmed it
  EXPECT_EQ(later.added, 0);
  EXPECT_EQ(later.candidates, 9);
}

// A pallet seen by one pass for 12 s, a forklift stopped for 8: the vehicle's beams ended at
// both all along. The pallet's candidates are added; the forklift's, held for less than
// confirm_min_gap_s, are not, nor is a hold from before the maps saw the place.
TEST_F(MergeTest, ACandidateHeldLongerThanTheGapIsAdded) {
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  Commit(Plan(e, {6, 9}), {6, 9});
  const int64_t centre = 9 * 20 + 9, corner = 8 * 20 + 8, free_cell = 5 * 20 + 5;
  const double gap = options_.confirm_min_gap_s;
  HeldReport report{{corner, centre, free_cell}, {6.5, 6.5, 6.5}, {6.5 + gap, 6.4 + gap, 20}};
  const std::vector<CellChange> adds =
      PlanHeldConfirmations(report, store_.candidates(), options_, nullptr, 0.05);
  ASSERT_EQ(adds.size(), 1u);  // the corner; the centre 0.1 s short; the free cell no candidate
  EXPECT_EQ(adds[0], (CellChange{corner, CellChangeKind::kAdded}));
  EXPECT_TRUE(PlanHeldConfirmations({{corner}, {10.0}, {10.0 + gap}}, store_.candidates(), options_,
                                    nullptr, 0.05)
                  .empty());   // held only after the map that saw it ended
  options_.confirmations = 1;  // adds at first sight: nothing is a candidate for long
  EXPECT_TRUE(PlanHeldConfirmations(report, store_.candidates(), options_, nullptr, 0.05).empty());
}

// Beams that end on a wall hold the cells in front of it as well: a held candidate within
// held_wall_clearance_m (0.2 m, 4 cells) of the wall on row 0 is not added, one beyond it is.
TEST_F(MergeTest, ACandidateHeldNextToAWallIsNotAdded) {
  PlacedEvidence e = Evidence();
  Set(e, 8, 3, 10, 3, kHit);  // 3 cells from the wall
  Set(e, 8, 6, 10, 6, kHit);  // 6 cells
  Commit(Plan(e, {6, 9}), {6, 9});
  const int64_t near_wall = 3 * 20 + 9, clear = 6 * 20 + 9;
  ASSERT_EQ(store_.candidates().count(near_wall), 1u);
  ASSERT_EQ(store_.candidates().count(clear), 1u);
  const double gap = options_.confirm_min_gap_s;
  const HeldReport report{{near_wall, clear}, {6.5, 6.5}, {7 + gap, 7 + gap}};
  const std::vector<uint8_t> walls = WallDistances(store_.static_map(), options_.thresholds);
  const std::vector<CellChange> adds =
      PlanHeldConfirmations(report, store_.candidates(), options_, &walls, 0.05);
  ASSERT_EQ(adds.size(), 1u);
  EXPECT_EQ(adds[0].cell, clear);
  options_.held_wall_clearance_m = 0.1;  // 2 cells: both are clear of it
  EXPECT_EQ(PlanHeldConfirmations(report, store_.candidates(), options_, &walls, 0.05).size(), 2u);
}

TEST(AggregatorHeldTest, TheHeldCandidatesEnterTheMapAsOneVersion) {
  using testing::BuildTempMap;
  const core::OccupancyGrid hall = testing::HallMap();
  const core::OccupancyGrid with_pallet = testing::HallMap(0.0, {{{15.0, 19.05}, {1.2, 0.8}}});
  auto aggregator = Aggregator::Create(hall, {});
  ASSERT_TRUE(aggregator.ok());
  EXPECT_TRUE(aggregator->ConfirmCandidatesHeld("v1", {{5}, {0.0}, {20.0}}, 21.0)->empty());
  EXPECT_EQ(aggregator->store().version(), 0u);  // no candidate: nothing changes
  testing::TempMapSpec spec;
  spec.start = {13.013, 16.027, 0.0};
  spec.start_s = 0, spec.end_s = 3, spec.sequence = 1;
  ASSERT_TRUE(aggregator->Submit(BuildTempMap(with_pallet, spec), 3).value().accepted);
  const std::vector<int64_t> cells = CandidateCells(aggregator->store().candidates());
  ASSERT_GT(cells.size(), 20u);  // the faces the vehicle saw, candidates after one map
  const uint64_t version = aggregator->store().version();
  const HeldReport held{cells, std::vector<double>(cells.size(), 1.0),
                        std::vector<double>(cells.size(), 12.0)};
  auto added = aggregator->ConfirmCandidatesHeld("v1", held, 12.5);
  ASSERT_TRUE(added.ok()) << added.status().ToString();
  EXPECT_EQ(*added, cells);
  EXPECT_EQ(aggregator->store().version(), version + 1);
  EXPECT_TRUE(aggregator->store().candidates().empty());
  for (int64_t c : cells) EXPECT_TRUE(aggregator->store().semi_static()[c]) << c;
}

// A person walking back and forth is at the same place again later, and no map need have seen
// the place free in between: a sighting more than confirm_max_gap_s later starts afresh.
TEST_F(MergeTest, ACandidateTooOldIsRenewedNotConfirmed) {
  options_.confirm_min_gap_s = 2.0;
  options_.confirm_max_gap_s = 20.0;
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  Commit(Plan(e, {0, 3}), {0, 3});
  const MergePlan late = Plan(e, {30, 33});  // 27 s after the first map: too late
  EXPECT_EQ(late.added, 0);
  EXPECT_EQ(late.candidates, 9);
  Commit(late, {30, 33});
  EXPECT_EQ(store_.candidates().at(9 * 20 + 9).first.start_s, 30.0);
  EXPECT_EQ(Plan(e, {36, 39}).added, 9);  // 3 s after the renewed sighting
  options_.confirm_max_gap_s = 40.0;      // with a longer window the old sighting confirms
  EXPECT_EQ(Plan(e, {30, 33}).added, 0);  // (the renewed one lies too close in time)
}

TEST_F(MergeTest, ACandidateSeenFreeIsDropped) {
  PlacedEvidence e = Evidence();
  Set(e, 8, 8, 10, 10, kHit);
  Commit(Plan(e, {0, 10}), {0, 10});
  Set(e, 8, 8, 10, 10, kFree);
  const MergePlan gone = Plan(e, {20, 30});
  EXPECT_EQ(gone.dropped, 9);
  Commit(gone, {20, 30});
  EXPECT_TRUE(store_.candidates().empty());
  EXPECT_EQ(Semi(), 0);
}

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

TEST(MergeOptionsTest, WallDistancesCountCellsToTheNearestOccupiedOne) {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 6, 4));  // unknown but one wall cell
  grid.SetState({1, 1}, core::CellState::kOccupied);
  const std::vector<uint8_t> d = WallDistances(grid, core::OccupancyThresholds{});
  EXPECT_EQ(d[1 * 6 + 1], 0);
  EXPECT_EQ(d[2 * 6 + 2], 1);  // diagonal neighbour: Chebyshev
  EXPECT_EQ(d[3 * 6 + 5], 4);
  EXPECT_EQ(d[0 * 6 + 0], 1);
  core::OccupancyGrid empty(core::GridGeometry(0.05, 3, 3));
  EXPECT_EQ(WallDistances(empty, core::OccupancyThresholds{})[4], 255);  // no wall at all
}

TEST(MergeOptionsTest, DistancesInMetresBecomeTheNearestWholeCells) {
  EXPECT_EQ(CellsFor(0.10, 0.05), 2);
  EXPECT_EQ(CellsFor(0.10, 0.03), 3);
  EXPECT_EQ(CellsFor(0.10, 0.02), 5);
  EXPECT_EQ(CellsFor(0.10, 0.10), 1);
  EXPECT_EQ(CellsFor(0.05, 0.10), 1);  // a distance > 0 is at least one cell
  EXPECT_EQ(CellsFor(0.0, 0.05), 0);
  const MergeCells c = MergeCellsFor(MergeOptions{}, 0.05);
  EXPECT_EQ(c.static_clearance, 2);  // the defaults at 5 cm are those chosen there in cells
  EXPECT_EQ(c.removal_clearance, 2);
  EXPECT_EQ(c.confirm_radius, 1);
}

// A wall at 2 cm keeps a clearance of 0.10 m, five cells, where nothing is added.
TEST(MergeOptionsTest, TheStaticClearanceIsTheSameDistanceAtAFinerResolution) {
  core::OccupancyGrid fine(core::GridGeometry(0.02, 20, 20));
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x)
      fine.SetState({x, y}, y == 0 ? core::CellState::kOccupied : core::CellState::kFree);
  const std::vector<uint8_t> addable = AddableCells(fine, MergeOptions{});
  EXPECT_EQ(addable[5 * 20 + 10], 0);  // 0.10 m from the wall
  EXPECT_EQ(addable[6 * 20 + 10], 1);  // 0.12 m
}

TEST(MergeOptionsTest, ValidateNamesTheBadField) {
  MergeOptions o;
  o.confirmations = 3;
  EXPECT_NE(o.Validate().message().find("confirmations"), std::string::npos);
  o = {};
  o.remove_max_log_odds = 1;
  EXPECT_NE(o.Validate().message().find("remove_max_log_odds"), std::string::npos);
  o = {};
  o.confirm_max_gap_s = o.confirm_min_gap_s;
  EXPECT_NE(o.Validate().message().find("confirm_max_gap_s"), std::string::npos);
  o = {};
  o.static_clearance_m = 2.0;  // a value in cells where metres are asked
  EXPECT_NE(o.Validate().message().find("static_clearance_m"), std::string::npos);
  o = {};
  o.wall_offset_window_m = -0.1;
  EXPECT_NE(o.Validate().message().find("wall_offset_window_m"), std::string::npos);
  o = MergeOptions();
  o.held_wall_clearance_m = 0.6;
  EXPECT_NE(o.Validate().message().find("held_wall_clearance_m"), std::string::npos);
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
