// One world's scores for one pipeline, read from the report.json that fleetmap-eval wrote
// (keys in docs/evaluation.md).
#pragma once

#include <cstdint>
#include <string>

#include "core/result.h"

namespace fleetmap::eval::suite {

struct WorldScore {
  double changed_f1 = 0.0;
  double added_recall = 0.0;           // NaN when nothing was added in the world
  double removed_recall = 0.0;         // NaN when nothing was taken away
  int64_t static_erased = 0;           // cells
  int64_t actor_mapped = 0;            // cells
  double align_trans_p95_cells = 0.0;  // NaN without an accepted merge
  // The same merges placed by their anchors alone (before the aggregator's correction); NaN
  // without an accepted merge or in a report that does not give it.
  double anchor_trans_p95_cells = 0.0;
  double anchor_nees_p95 = 0.0;     // NaN where no map sent its anchor's covariance
  double localization_p95_m = 0.0;  // the vehicles' pose error; NaN where the run has none
  // Truly added cells missed where a candidate was dropped as seen free, of all truly added
  // cells; NaN when nothing was added or the report does not give it.
  double added_lost_seen_free = 0.0;
  // p95 over the temporary maps of how far the vehicles' builders drifted within a map
  // (metres, degrees); NaN for perfect maps and in a report that does not give it.
  double tempmap_drift_p95_m = 0.0;
  double tempmap_drift_p95_deg = 0.0;
  int merges_accepted = 0;
  int merges_rejected = 0;
  double run_s = 0.0;  // wall-clock seconds of the run

  // Rejected of all merges; NaN without any merge.
  double RejectedShare() const;
};

// DataLoss names the key that is missing or not a number; null reads as NaN.
core::Result<WorldScore> ReadWorldScore(const std::string& report_json_path);

}  // namespace fleetmap::eval::suite
