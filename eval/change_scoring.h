// Map quality against the truth. The truth of a changed cell is what the fleet's scanners
// could have known (the simulator's ObservationLog): a cell of a semi-static object is truly
// added if the last beam to reach it hit it, truly removed if it was hit once and the last
// beam went through it. Predictions come from the run's map: a non-static cell occupied at the
// end is predicted added; one occupied in some version and not at the end, predicted removed.
// Matching allows `tolerance_cells` (Chebyshev distance), since a merged edge one cell off is
// still the right edge.
#pragma once

#include <optional>

#include "eval/run_record.h"
#include "sim/observation_log.h"
#include "sim/world.h"

namespace fleetmap::eval {

struct ChangeScores {
  int64_t true_added = 0, true_removed = 0;
  int64_t predicted_added = 0, predicted_removed = 0;
  int64_t correct_added = 0, correct_removed = 0;    // predictions that match a truth
  int64_t recalled_added = 0, recalled_removed = 0;  // truths that a prediction matches
  // Shares, NaN where undefined: a precision without predictions, a recall without truths,
  // an F1 without either (a run in which nothing changed scores nothing).
  double precision = 0.0, recall = 0.0, f1 = 0.0;  // both kinds together
  double added_precision = 0.0, added_recall = 0.0;
  double removed_precision = 0.0, removed_recall = 0.0;
  int64_t static_cells_erased = 0;  // occupied in the static map, not in the final map
  int64_t actor_cells_mapped = 0;   // swept by an actor, no object's or wall's, yet occupied
  // Candidates dropped because a vehicle saw them free (unset when the run does not record
  // them): all of them, those within tolerance of a truly added cell, and the truly added
  // cells missed at the end with such a drop within tolerance (what the drops cost).
  std::optional<int64_t> seen_free_drops, seen_free_drops_near_added, added_missed_seen_free;
};

struct ScoringOptions {
  int tolerance_cells = 1;
  double actor_sample_period_s = 0.05;  // how finely actor paths are swept
};

ChangeScores ScoreChanges(const sim::World& world, const sim::ObservationLog& observations,
                          const RunRecord& run, const ScoringOptions& options = {});

// Per cell: a candidate within `tolerance_cells` (Chebyshev) was dropped as seen free. Empty
// when the run does not record such drops.
std::vector<uint8_t> NearSeenFreeDrops(const RunRecord& run, const core::GridGeometry& geometry,
                                       int tolerance_cells = 1);

// Cells an actor's disc covered at some time of the scenario.
std::vector<uint8_t> ActorSweptCells(const sim::World& world, double sample_period_s);

}  // namespace fleetmap::eval
