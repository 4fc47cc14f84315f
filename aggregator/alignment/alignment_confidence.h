// How far to trust a correction. Every alignment gets a score from its evidence (matched
// line length, the spread of the residuals, how much more of the temporary map the static
// map explains after the correction than before) and is rejected, with a reason, when the
// temporary map holds too few static lines (the paper's third assumption, Sec. 3.1), when
// the evidence disagrees, or when the correction exceeds what localization can be off by
// (the first assumption). A rejected map is never merged (see aggregator.h).
#pragma once

#include <cmath>
#include <string>

#include "aggregator/alignment/alignment.h"
#include "aggregator/alignment/cell_alignment.h"

namespace fleetmap::aggregator {

enum class RejectReason {
  kNone = 0,
  kInvalidTempMap,      // bad input: resolution, size, outside the map, not finite
  kTooFewStaticLines,   // too little matched static line length
  kLinesDisagree,       // matched lines leave large residuals in angle or distance
  kAmbiguousShift,      // the overlap search along the lines has no distinct peak
  kCorrectionTooLarge,  // beyond the localization error the system assumes
  kOverlapWorse,        // the correction explains less of the map than the anchor did
  kLowOverlap,          // the static map explains too little of the placed map
};
// "too_few_static_lines" style names, for reports and messages.
const char* RejectReasonName(RejectReason reason);

struct ConfidenceOptions {
  // Matched temporary segments, >= 1, and their total length, >= 0. One long wall is enough:
  // it fixes the rotation and the shift across it, and the overlap search (with its own
  // checks below) the shift along it. (2 lines rejected maps the evaluation aligned well.)
  int min_matched_lines = 1;
  double min_matched_length_m = 2.0;
  // Weighted median |normal distance| after correction, metres (at least one cell of the
  // map: a line's position is known to a cell's quantisation at best); 1.5 cells at 0.05 m.
  double max_residual_m = 0.075;
  double max_angle_residual_rad = 2.0 * M_PI / 180;  // weighted median |angle difference|
  double max_correction_m = 0.75;                    // the anchor's displacement
  double max_correction_rad = 6.0 * M_PI / 180;
  // Of the overlap search, when one was used: the peak must rise this much (relative) above
  // the lowest score of the range, and not lie at its end.
  double min_prominence = 0.02;
  // ... and rise above any other local peak (0.15 m or more away) by at least this fraction
  // of its rise above the lowest score, [0, 1] (OverlapPeak::Distinctness). In an aisle whose
  // only structure across it was a pillar's arc and a pallet, a shift 10 cells off scored
  // 0.5 % better than the true one (distinctness 0.26, prominence 0.04) and smeared the pallet
  // along the aisle. Such a map is rejected as ambiguous; the vehicle's next one sees more.
  // No map of the evaluation's truthmaps or agents runs with the default settings falls below.
  double min_distinctness = 0.3;
  double max_overlap_loss = 0.02;        // explained fraction may drop at most this much
  double min_explained_fraction = 0.25;  // of the temporary surface cells, after correction
  core::Status Validate() const;
};

struct AlignmentConfidence {
  int matched_lines = 0;
  double matched_length_m = 0.0;
  double residual_cells = 0.0;      // weighted median |normal distance|, cells
  double angle_residual_deg = 0.0;  // weighted median |angle difference|
  double explained_before = 0.0;    // fraction of temporary surface cells near static ones
  double explained_after = 0.0;
  double overlap_gain = 0.0;  // after - before
  double prominence = 1.0;    // of the overlap peak (1 when no search was used)
  double distinctness = 1.0;  // of the overlap peak over its rival (1 when no search was used)
  double score = 0.0;         // 0..1, higher is better; for reports and ordering
  // The correction's move of the anchor against the anchor's covariance (anchor_gate.h); NaN
  // when the vehicle sent no covariance.
  double anchor_mahalanobis_sq = NAN;
  bool anchor_stands = false;  // the correction was not taken: placed where the vehicle put it
  RejectReason reason = RejectReason::kNone;
  std::string explanation;  // for a rejection: what was measured against what limit
  bool accepted() const { return reason == RejectReason::kNone; }
};

// `explained_before` / `after`: ExplainedFraction of the temporary surface cells placed by
// the anchor alone and with the correction.
AlignmentConfidence AssessAlignment(const AlignmentResult& alignment, double resolution_m,
                                    double explained_before, double explained_after,
                                    const ConfidenceOptions& options);

// A cell alignment, judged by the same limits: its peak must be distinct and inside its
// window, and the static map must explain as much of the placed map as the anchor's
// placement did (less max_overlap_loss) and at least min_explained_fraction.
AlignmentConfidence AssessCellAlignment(const CellAlignment& cells, double explained_before,
                                        double explained_after, const ConfidenceOptions& options);

// The lines' correction, accepted by its own limits, judged again where the cells found
// another pose almost as good: `relative` is where the lines' pose scores in the cells'
// window (CellAlignment::Relative); below `min_relative` it fits worse than the rival that
// made the cells ambiguous, and the map is ambiguous (kAmbiguousShift).
void RejectBelowCellRival(double relative, double min_relative, AlignmentConfidence& lines);

}  // namespace fleetmap::aggregator
