// The aggregator: the server's half of the paper as a library (no LCM, no I/O but its own
// persistence folder). A temporary map is checked, its lines are extracted and matched to
// the static map's, the correction is computed and judged, and an accepted map is merged
// into the versioned current map, journaled before it is acknowledged.
//
// A rejected map (bad input, or an alignment the evidence does not support) is never
// merged: the current map, its version and the journal stay untouched, and the report says
// why. Whoever sent it learns the reason from the acknowledgement (TEMPMAP_ACK) and the
// MERGE_REPORT; a vehicle that keeps seeing the change builds a new temporary map, which
// then usually holds more of the building's lines. Counts per reason are kept in stats().
#pragma once

#include <array>
#include <optional>
#include <string>

#include "aggregator/alignment/alignment_confidence.h"
#include "aggregator/alignment/anchor_gate.h"
#include "aggregator/alignment/placement.h"
#include "aggregator/alignment/static_features.h"
#include "aggregator/candidates_seen_free.h"
#include "aggregator/current_map_store.h"
#include "aggregator/merge.h"
#include "aggregator/persistence/map_persistence.h"

namespace fleetmap::aggregator {

struct AggregatorOptions {
  PlacementOptions placement;
  LineFeatureOptions temp_lines;         // line extraction of temporary maps
  StaticFeatureOptions static_features;  // line extraction and overlap fields of the static map
  AlignmentOptions alignment;
  // The temporary map's cells matched to the static map's around the anchor: first (the
  // lines' correction where it is rejected), only where the lines' correction is rejected
  // (too few lines, lines that disagree, a worse fit), or never (docs/aggregator.md).
  CellAlignmentOptions cell_alignment;
  ConfidenceOptions confidence;
  // An accepted correction the anchor's covariance does not allow, or that does not fit
  // better, is not taken: the anchor stands (anchor_gate.h).
  AnchorGateOptions anchor_gate;
  MergeOptions merge;
  StoreOptions store;
  PersistenceOptions persistence;  // used by Open only
  core::Status Validate() const;
};

// One row of the paper's Tables 1 and 2.
struct LineReportRow {
  int temp_line_id = 0;           // index into the temporary map's segments
  int static_line_id = 0;         // index into StaticMapFeatures::lines()
  double distance_diff_px = 0.0;  // |normal distance| after the correction, cells
  double angle_diff_deg = 0.0;    // static minus corrected temporary angle
};

// Everything up to the decision; computing it changes nothing.
struct Assessment {
  RejectReason reason = RejectReason::kNone;
  std::string reason_text;
  AlignmentResult alignment;
  AlignmentConfidence confidence;
  int temp_lines = 0;  // segments found in the temporary map
  bool accepted() const { return reason == RejectReason::kNone; }
};

struct MergeReport {
  std::string vehicle_id;
  int32_t tempmap_sequence = 0;
  bool accepted = false;
  RejectReason reason = RejectReason::kNone;
  std::string reason_text;
  core::Pose2 correction;  // placed = correction * anchor
  AlignmentResult alignment;
  AlignmentConfidence confidence;
  std::vector<LineReportRow> lines;
  int cells_added = 0;
  int cells_removed = 0;
  int candidates_new = 0;      // cells seen occupied for the first time (merge.h)
  int candidates_dropped = 0;  // candidates seen free
  uint64_t version = 0;        // the current map's version after this report
  MapDelta delta;              // version - 1 -> version; empty when rejected
  std::string warning;         // e.g. a snapshot that failed after the merge was journaled
};

struct AggregatorStats {
  int accepted = 0;
  int rejected = 0;
  std::array<int, 8> rejected_by_reason{};  // indexed by RejectReason
};

class Aggregator {
 public:
  // In memory only. Fails on invalid options or a static map without usable geometry.
  static core::Result<Aggregator> Create(core::OccupancyGrid static_map,
                                         const AggregatorOptions& options);
  // With persistence in `state_folder`: restores the current map from its snapshot and
  // journal (see map_persistence.h) and journals every accepted merge.
  static core::Result<Aggregator> Open(core::OccupancyGrid static_map,
                                       const AggregatorOptions& options,
                                       const std::string& state_folder,
                                       RestoreReport* report = nullptr);

  // Checks, extracts lines, aligns and judges. Never changes anything.
  Assessment Assess(const core::TempMap& map) const;
  // Merges an accepted assessment of `map` (from Assess on the same map): journal first
  // (IoError: nothing happened), then the current map. A rejected one gives its report.
  core::Result<MergeReport> Commit(const core::TempMap& map, const Assessment& assessment,
                                   double now_s);
  // Assess, then Commit. `now_s` is recorded as the merge time (time is passed in).
  core::Result<MergeReport> Submit(const core::TempMap& map, double now_s);

  // Drops the candidates `vehicle_id` saw empty (PlanCandidateDrops), journaled as one commit
  // of a new version; nothing (no version) when the report justifies no drop. Returns the
  // cells dropped, ascending.
  core::Result<std::vector<int64_t>> DropCandidatesSeenFree(const std::string& vehicle_id,
                                                            const SeenFreeReport& report,
                                                            double now_s);

  // Adds the candidates a vehicle's beams kept ending at long enough (PlanHeldConfirmations);
  // returns the cells added, ascending.
  core::Result<std::vector<int64_t>> ConfirmCandidatesHeld(const std::string& vehicle_id,
                                                           const HeldReport& report, double now_s);

  // Writes a snapshot now (persistence only; FailedPrecondition without).
  core::Status WriteSnapshot();

  const CurrentMapStore& store() const { return store_; }
  const StaticMapFeatures& static_features() const { return features_; }
  const AggregatorOptions& options() const { return options_; }
  const AggregatorStats& stats() const { return stats_; }

 private:
  Aggregator(AggregatorOptions options, StaticMapFeatures features, CurrentMapStore store)
      : options_(std::move(options)),
        features_(std::move(features)),
        store_(std::move(store)),
        wall_distance_(WallDistances(store_.static_map(), options_.merge.thresholds)),
        addable_(AddableCells(store_.static_map(), options_.merge, wall_distance_)) {}
  MergeReport Rejected(const core::TempMap& map, const Assessment& assessment);
  // Commits what a vehicle's report of candidates justifies, as a version of its own (no
  // temporary map: kSeenFreeSequence); returns the cells changed.
  core::Result<std::vector<int64_t>> CommitReport(const std::string& vehicle_id,
                                                  const TimeSpan& span,
                                                  std::vector<CellChange> changes, double now_s);
  // The two ways of aligning, judged; `points` the subsampled surface cells, `before` how much
  // of them the static map explains at the anchor.
  Assessment ByLines(const AlignmentInput& in, const std::vector<Eigen::Vector2d>& points,
                     double before) const;
  Assessment ByCells(const AlignmentInput& in, const std::vector<Eigen::Vector2d>& points,
                     double before, CellAlignment* cells) const;
  // Where the cells found another pose almost as good, rejects the lines' correction that
  // chose a pose the cells score lower than such a rival (CellAlignmentOptions).
  // The anchor gate on an accepted assessment: the correction taken, or the anchor standing
  // (rejected when the static map does not explain enough of the map placed by it).
  void KeepAnchorUnlessProven(const core::TempMap& map, const AlignmentInput& in,
                              Assessment& a) const;
  void CheckLinesAmongCellPeaks(const AlignmentInput& in, const CellAlignment& cells,
                                Assessment& lines) const;
  // A rejected assessment accepted at the anchor where the vehicle knew it well enough and
  // the static map explains the map placed there (AnchorGateOptions::stand_max_*).
  void StandWhereKnownWell(const core::TempMap& map, const AlignmentInput& in, Assessment& a) const;
  // The assessment's map placed where its vehicle put it (no correction), `why` leading the
  // explanation.
  void PlaceAtAnchor(const AlignmentInput& in, const std::string& why, Assessment& a) const;

  AggregatorOptions options_;
  StaticMapFeatures features_;
  CurrentMapStore store_;
  std::vector<uint8_t> wall_distance_;  // WallDistances of the static map
  std::vector<uint8_t> addable_;        // AddableCells of the static map, from them
  std::optional<MapPersistence> persistence_;
  AggregatorStats stats_;
};

}  // namespace fleetmap::aggregator
