// The messages of the candidate watch (docs/architecture.md): the aggregator's candidates,
// sent in parts of one datagram each, and a vehicle's reports of candidates it saw free or
// held.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "aggregator/candidates_seen_free.h"
#include "core/result.h"
#include "fleetmap/candidates_free_t.hpp"
#include "fleetmap/candidates_held_t.hpp"
#include "fleetmap/map_candidates_t.hpp"

namespace fleetmap::aggregator::node {

// The whole set in parts of at most kMaxCandidateCellsPerMessage cells; one message with no
// cells and parts 0 when there are none (the vehicles then forget theirs).
std::vector<fleetmap::map_candidates_t> CandidateMessages(
    const std::map<int64_t, Candidate>& candidates, uint64_t version, int64_t utime);

// A vehicle's report, checked: at most kMaxCandidateCellsPerMessage cells, each a cell of a
// map of `num_cells`, pass times in order. InvalidArgument naming what is wrong.
core::Result<SeenFreeReport> SeenFreeFromMessage(const fleetmap::candidates_free_t& message,
                                                 int64_t num_cells);

// ... and its report of candidates held: 1 to kMaxHeldCellsPerMessage cells inside the map,
// each held from before until.
core::Result<HeldReport> HeldFromMessage(const fleetmap::candidates_held_t& message,
                                         int64_t num_cells);

}  // namespace fleetmap::aggregator::node
