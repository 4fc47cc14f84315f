#include "aggregator/alignment/alignment_confidence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "aggregator/alignment/alignment_steps.h"

namespace fleetmap::aggregator {
namespace {

std::string Format(const char* format, double a, double b) {
  char buf[160];
  std::snprintf(buf, sizeof(buf), format, a, b);
  return buf;
}

void Measure(const AlignmentResult& a, double resolution_m, AlignmentConfidence& c) {
  std::vector<Weighted> distances, angles;
  for (const LineMatch& m : a.matches) {
    ++c.matched_lines;
    c.matched_length_m += m.weight_m;
    distances.push_back({std::abs(m.offset_m) / resolution_m, m.weight_m});
    angles.push_back({std::abs(m.angle_diff_rad) * 180 / M_PI, m.weight_m});
  }
  c.residual_cells = WeightedMedian(distances);
  c.angle_residual_deg = WeightedMedian(angles);
  c.prominence = a.shift_by_overlap ? a.overlap.Prominence() : 1.0;
  c.distinctness = a.shift_by_overlap ? a.overlap.Distinctness() : 1.0;
}

// The first failed check, in order of how fundamental it is.
void Judge(const AlignmentResult& a, const ConfidenceOptions& o, double resolution_m,
           AlignmentConfidence& c) {
  const double moved = std::hypot(a.dx_m, a.dy_m);
  const double max_residual_cells =
      std::max(1.0, core::MetresInCells(o.max_residual_m, resolution_m));
  auto reject = [&](RejectReason reason, std::string why) {
    c.reason = reason;
    c.explanation = std::move(why);
  };
  if (c.matched_lines < o.min_matched_lines || c.matched_length_m < o.min_matched_length_m) {
    reject(RejectReason::kTooFewStaticLines, Format("%.0f static lines matched, %.2f m long",
                                                    double(c.matched_lines), c.matched_length_m));
  } else if (c.residual_cells > max_residual_cells) {
    reject(RejectReason::kLinesDisagree,
           Format("median line residual %.2f cells > %.2f", c.residual_cells, max_residual_cells));
  } else if (c.angle_residual_deg > o.max_angle_residual_rad * 180 / M_PI) {
    reject(RejectReason::kLinesDisagree,
           Format("median angle residual %.2f deg > %.2f", c.angle_residual_deg,
                  o.max_angle_residual_rad * 180 / M_PI));
  } else if (moved > o.max_correction_m || std::abs(a.dtheta_rad) > o.max_correction_rad) {
    reject(RejectReason::kCorrectionTooLarge,
           Format("correction %.3f m, %.2f deg", moved, a.dtheta_rad * 180 / M_PI));
  } else if (c.prominence < o.min_prominence) {
    reject(RejectReason::kAmbiguousShift,
           Format("overlap peak prominence %.4f < %.4f", c.prominence, o.min_prominence));
  } else if (c.distinctness < o.min_distinctness) {
    reject(RejectReason::kAmbiguousShift,
           Format("another shift fits almost as well: overlap peak distinctness %.3f < %.3f",
                  c.distinctness, o.min_distinctness));
  } else if (a.shift_by_overlap && a.overlap.at_edge) {
    reject(RejectReason::kAmbiguousShift,
           Format("overlap peak at the end of its range (%.3f m, score %.3f)", a.overlap.shift_m,
                  a.overlap.score));
  } else if (c.explained_after < c.explained_before - o.max_overlap_loss) {
    reject(RejectReason::kOverlapWorse, Format("explained fraction fell from %.3f to %.3f",
                                               c.explained_before, c.explained_after));
  } else if (c.explained_after < o.min_explained_fraction) {
    reject(RejectReason::kLowOverlap,
           Format("explained fraction %.3f < %.3f", c.explained_after, o.min_explained_fraction));
  }
}

}  // namespace

const char* RejectReasonName(RejectReason reason) {
  switch (reason) {
    case RejectReason::kNone:
      return "none";
    case RejectReason::kInvalidTempMap:
      return "invalid_temp_map";
    case RejectReason::kTooFewStaticLines:
      return "too_few_static_lines";
    case RejectReason::kLinesDisagree:
      return "lines_disagree";
    case RejectReason::kAmbiguousShift:
      return "ambiguous_shift";
    case RejectReason::kCorrectionTooLarge:
      return "correction_too_large";
    case RejectReason::kOverlapWorse:
      return "overlap_worse";
    case RejectReason::kLowOverlap:
      return "low_overlap";
  }
  return "unknown";
}

core::Status ConfidenceOptions::Validate() const {
  if (min_matched_lines < 1)
    return core::InvalidArgument("confidence.min_matched_lines must be >= 1");
  if (!(min_matched_length_m >= 0))
    return core::InvalidArgument("confidence.min_matched_length_m must be >= 0");
  if (!(max_residual_m > 0)) return core::InvalidArgument("confidence.max_residual_m must be > 0");
  if (!(max_angle_residual_rad > 0))
    return core::InvalidArgument("confidence.max_angle_residual_rad must be > 0");
  if (!(max_correction_m > 0))
    return core::InvalidArgument("confidence.max_correction_m must be > 0");
  if (!(max_correction_rad > 0))
    return core::InvalidArgument("confidence.max_correction_rad must be > 0");
  if (!(min_prominence >= 0 && min_prominence < 1))
    return core::InvalidArgument("confidence.min_prominence must be in [0, 1)");
  if (!(min_distinctness >= 0 && min_distinctness <= 1))
    return core::InvalidArgument("confidence.min_distinctness must be in [0, 1]");
  if (!(max_overlap_loss >= 0))
    return core::InvalidArgument("confidence.max_overlap_loss must be >= 0");
  if (!(min_explained_fraction >= 0 && min_explained_fraction <= 1))
    return core::InvalidArgument("confidence.min_explained_fraction must be in [0, 1]");
  return core::OkStatus();
}

AlignmentConfidence AssessAlignment(const AlignmentResult& alignment, double resolution_m,
                                    double explained_before, double explained_after,
                                    const ConfidenceOptions& options) {
  AlignmentConfidence c;
  c.explained_before = explained_before;
  c.explained_after = explained_after;
  c.overlap_gain = explained_after - explained_before;
  Measure(alignment, resolution_m, c);
  Judge(alignment, options, resolution_m, c);
  const double length_term =
      std::min(1.0, c.matched_length_m / (4.0 * options.min_matched_length_m));
  c.score = length_term * explained_after / (1.0 + c.residual_cells);
  if (!c.accepted()) c.score = 0.0;
  return c;
}

AlignmentConfidence AssessCellAlignment(const CellAlignment& cells, double explained_before,
                                        double explained_after, const ConfidenceOptions& o) {
  AlignmentConfidence c;
  c.explained_before = explained_before;
  c.explained_after = explained_after;
  c.overlap_gain = explained_after - explained_before;
  c.distinctness = cells.distinctness;
  if (cells.at_edge) {
    c.reason = RejectReason::kAmbiguousShift;
    c.explanation = Format("best pose at the edge of the window (score %.3f, at the anchor %.3f)",
                           cells.score, cells.at_anchor);
  } else if (c.distinctness < o.min_distinctness) {
    c.reason = RejectReason::kAmbiguousShift;
    c.explanation = Format("another pose fits almost as well: distinctness %.3f < %.3f",
                           c.distinctness, o.min_distinctness);
  } else if (explained_after < explained_before - o.max_overlap_loss) {
    c.reason = RejectReason::kOverlapWorse;
    c.explanation =
        Format("explained fraction fell from %.3f to %.3f", explained_before, explained_after);
  } else if (explained_after < o.min_explained_fraction) {
    c.reason = RejectReason::kLowOverlap;
    c.explanation =
        Format("explained fraction %.3f < %.3f", explained_after, o.min_explained_fraction);
  }
  c.score = c.accepted() ? explained_after * cells.distinctness : 0.0;
  return c;
}

void RejectBelowCellRival(double relative, double min_relative, AlignmentConfidence& lines) {
  if (!lines.accepted() || relative >= min_relative) return;
  lines.reason = RejectReason::kAmbiguousShift;
  lines.explanation = Format(
      "the pose fits the cells worse than their rival: %.2f of the way from the window's "
      "lowest score to its best < %.2f",
      relative, min_relative);
  lines.score = 0.0;
}

}  // namespace fleetmap::aggregator
