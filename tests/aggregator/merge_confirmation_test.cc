// What a merge adds and how a candidate is confirmed: by a second map of another time, by a
// watch longer than the gap, or held by a vehicle's beams; and how a candidate is dropped or
// renewed instead.
#include <gtest/gtest.h>

#include <vector>

#include "aggregator/aggregator.h"
#include "aggregator/candidates_seen_free.h"
#include "aggregator/current_map_store.h"
#include "aggregator/merge.h"
#include "tests/aggregator/merge_fixture.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

using testing::Evidence;
using testing::kFree;
using testing::kHit;
using testing::MergeTest;
using testing::Set;

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

}  // namespace
}  // namespace fleetmap::aggregator
