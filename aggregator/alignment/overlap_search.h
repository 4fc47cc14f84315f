// The paper's dx (Sec. 3.4): the shift along one direction at which the placed temporary
// map overlaps the static map most. The paper counts temporary cells that land on occupied
// static cells, at whole-cell shifts; our mode scores the smooth surface field instead and
// refines the peak to a fraction of a cell. Both report how far the score rises above its
// lowest value in the range and whether the best shift lies at the end of the range, so a
// flat score (a corridor with nothing across it) is recognised as ambiguous, not trusted.
#pragma once

#include <vector>

#include "aggregator/alignment/static_features.h"

namespace fleetmap::aggregator {

enum class OverlapScore {
  kOccupiedCells,  // the paper: the fraction of points on occupied static cells
  kSurfaceField,   // ours: the mean of StaticMapFeatures::SurfaceField over the points
};

struct OverlapSearchOptions {
  OverlapScore score = OverlapScore::kSurfaceField;
  double range_m = 0.5;  // shifts in [-range, range] are tried, > 0
  double step_m = 0.05;  // step of the search (one cell at 5 cm), > 0
  // > 0: around the best step, steps of this size, then a parabola through the best three.
  double refine_step_m = 0.0125;
  // Another local peak at least this far from the best one is its rival (see
  // OverlapPeak::Distinctness), metres >= step_m.
  double rival_separation_m = 0.15;
  core::Status Validate() const;
};

struct OverlapPeak {
  double shift_m = 0.0;  // along the direction
  double score = 0.0;    // at the best shift
  double lowest = 0.0;   // the lowest score in the range
  double at_zero = 0.0;  // at shift 0
  bool at_edge = false;  // the best whole step is the first or last of the range
  // Of the whole steps: the best score, and the best of the other local peaks at least
  // rival_separation_m away (the lowest score when there is none).
  double step_best = 0.0;
  double rival = 0.0;
  // (score - lowest) / score: 0 for a flat score, larger for a pronounced peak.
  double Prominence() const { return score > 0 ? (score - lowest) / score : 0.0; }
  // (step_best - rival) / (step_best - lowest): 1 for a single peak, near 0 when another
  // shift fits almost as well. Points on the walls along the direction score the same at
  // every shift and dilute the prominence; this compares the peaks' rise alone.
  double Distinctness() const {
    const double rise = step_best - lowest;
    return rise > 0 ? (step_best - rival) / rise : 0.0;
  }
};

// Mean score of the points (static frame) shifted by `shift`.
double OverlapScoreAt(const StaticMapFeatures& features, const std::vector<Eigen::Vector2d>& points,
                      const Eigen::Vector2d& shift, OverlapScore score);

OverlapPeak SearchShift(const StaticMapFeatures& features,
                        const std::vector<Eigen::Vector2d>& points_in_map,
                        const Eigen::Vector2d& direction, const OverlapSearchOptions& options);

// Fraction of the points whose surface field is at least 0.5 (within about one sigma of a
// static surface): how much of what the temporary map saw the static map explains.
double ExplainedFraction(const StaticMapFeatures& features,
                         const std::vector<Eigen::Vector2d>& points_in_map);

}  // namespace fleetmap::aggregator
