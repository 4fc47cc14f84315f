// Candidates a vehicle saw empty: its beams passed through them, none ending there, after the
// last temporary map that saw them occupied. Such a candidate was something that left (a
// person at a turning point, a forklift at its stop) and is dropped; a second sighting later
// starts it afresh instead of confirming it (docs/aggregator.md, "People and forklifts").
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "aggregator/merge.h"
#include "core/map/seen_free_cells.h"

namespace fleetmap::aggregator {

// One vehicle's report: the cells and the first and last scan that passed through them.
using SeenFreeReport = core::SeenFreeCells;

// The candidates' cells, ascending: what the vehicles watch.
std::vector<int64_t> CandidateCells(const std::map<int64_t, Candidate>& candidates);

// The temporary-map sequence a commit of such drops records: it comes from no temporary map.
constexpr int32_t kSeenFreeSequence = -1;

// The drops the report justifies, ascending by cell: cells that are still candidates and were
// last seen occupied by a map that ended before the report's first pass (an older report
// says nothing about a sighting after it).
std::vector<CellChange> PlanCandidateDrops(const SeenFreeReport& report,
                                           const std::map<int64_t, Candidate>& candidates);

// A vehicle's report of candidates its beams kept ending at.
using HeldReport = core::HeldCells;

// The confirmations the report justifies, ascending by cell: cells that are still candidates,
// held at least confirm_min_gap_s, the hold overlapping the maps that saw them, and farther
// than held_wall_clearance_m from a static wall. `wall_distance`: the static map's
// WallDistances on a grid of `resolution_m` (null: no wall is near).
std::vector<CellChange> PlanHeldConfirmations(const HeldReport& report,
                                              const std::map<int64_t, Candidate>& candidates,
                                              const MergeOptions& options,
                                              const std::vector<uint8_t>* wall_distance,
                                              double resolution_m);

}  // namespace fleetmap::aggregator
