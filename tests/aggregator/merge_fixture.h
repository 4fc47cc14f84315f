// The merge planner on a small map, for the tests of what a merge adds, confirms, drops and
// removes: a 20 x 20 cell map at 5 cm with a wall on row 0, evidence set by hand cell by cell,
// and a fixture that plans a merge against a CurrentMapStore and commits it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "aggregator/current_map_store.h"
#include "aggregator/merge.h"

namespace fleetmap::aggregator::testing {

inline constexpr float kHit = 4.6f, kFree = -4.6f;

// 20 x 20 cells at 5 cm: a wall on row 0, free elsewhere.
inline core::OccupancyGrid SmallMap() {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 20, 20));
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x)
      grid.SetState({x, y}, y == 0 ? core::CellState::kOccupied : core::CellState::kFree);
  return grid;
}

// Evidence over the whole map, 0 (unobserved) except where set.
inline PlacedEvidence Evidence() {
  PlacedEvidence e;
  e.map_width = 20;
  e.window = {0, 0, 20, 20};
  e.log_odds.assign(400, 0.0f);
  return e;
}

// Log-odds `l` on the cells from (x0, y0) to (x1, y1), both included.
inline void Set(PlacedEvidence& e, int x0, int y0, int x1, int y1, float l) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) e.log_odds[size_t(y) * 20 + x] = l;
}

// Plans merges against a store of SmallMap() as the aggregator does, and commits them as
// vehicle v1's map 1; a test sets options_ and wall_distance_ between plans.
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

}  // namespace fleetmap::aggregator::testing
