#include "aggregator/alignment/line_features.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::aggregator {

core::Status LineFeatureOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(thresholds.Validate());
  if (!(strong_log_odds > core::ProbabilityToLogOdds(thresholds.occupied_probability)))
    return core::InvalidArgument("lines.strong_log_odds must lie above the occupied threshold");
  if (!(min_length_m >= 0 && min_vote_length_m > 0 && max_hough_gap_m >= 0 &&
        max_join_gap_m >= 0)) {
    return core::InvalidArgument(
        "lines: need min_length_m >= 0, min_vote_length_m > 0, max_hough_gap_m >= 0, "
        "max_join_gap_m >= 0");
  }
  FLEETMAP_RETURN_IF_ERROR(HoughOptionsFor(*this, 0.05).Validate());
  return ConsolidationOptionsFor(*this, 0.05).Validate();
}

HoughOptions HoughOptionsFor(const LineFeatureOptions& o, double resolution_m) {
  HoughOptions h;
  h.rho_cells = 1.0;
  h.theta_step_rad = o.theta_step_rad;
  h.min_votes = std::max(3, static_cast<int>(std::lround(o.min_vote_length_m / resolution_m)));
  h.min_length_cells = std::max(2.0, core::MetresInCells(o.min_length_m, resolution_m));
  h.max_gap_cells = std::max(1.0, core::MetresInCells(o.max_hough_gap_m, resolution_m));
  return h;
}

ConsolidationOptions ConsolidationOptionsFor(const LineFeatureOptions& o, double resolution_m) {
  ConsolidationOptions c;
  c.max_angle_diff_rad = o.max_angle_diff_rad;
  c.max_normal_distance_cells = o.max_join_distance_cells;
  c.max_gap_cells = std::max(1.0, core::MetresInCells(o.max_join_gap_m, resolution_m));
  c.fit_band_cells = o.fit_band_cells;
  c.min_length_cells = std::max(2.0, core::MetresInCells(o.min_length_m, resolution_m));
  c.min_fit_pixels = o.min_fit_pixels;
  return c;
}

LineSegment CellSegmentToFrame(const LineSegment& cells, const core::GridGeometry& geometry) {
  return cells.Scaled(geometry.resolution_m()).Transformed(geometry.origin());
}

namespace {

// Orients a segment (in the grid's frame) so that the side the grid holds free lies on its
// left, when exactly one side, two cells from the mid point, is free.
LineSegment Orient(LineSegment s, const core::OccupancyGrid& grid,
                   const core::OccupancyThresholds& thresholds) {
  const core::GridGeometry& g = grid.geometry();
  const core::TriStateClassifier classify(thresholds);
  const Eigen::Vector2d d = s.direction();
  const Eigen::Vector2d left = 2.0 * g.resolution_m() * Eigen::Vector2d(-d.y(), d.x());
  auto free_at = [&](const Eigen::Vector2d& p) {
    const core::CellIndex c = g.WorldToCell(p);
    return g.Contains(c) && classify(grid.log_odds(c)) == core::CellState::kFree;
  };
  const bool free_left = free_at(s.midpoint() + left), free_right = free_at(s.midpoint() - left);
  if (free_left == free_right) return s;
  if (free_right) std::swap(s.a, s.b);
  s.oriented = true;
  return s;
}

}  // namespace

core::Result<LineFeatures> ExtractLineFeatures(const core::OccupancyGrid& grid,
                                               const LineFeatureOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  LineFeatures features;
  features.edges = options.source == EdgeSource::kSurfaceCells
                       ? SurfaceCells(grid, options.thresholds)
                       : CellsAtLeast(grid, options.strong_log_odds);
  std::vector<LineSegment> raw;
  const double resolution_m = grid.geometry().resolution_m();
  FLEETMAP_ASSIGN_OR_RETURN(
      raw, DetectHoughSegments(features.edges, HoughOptionsFor(options, resolution_m)));
  features.raw_segments = static_cast<int>(raw.size());
  for (const LineSegment& s :
       ConsolidateSegments(raw, features.edges, ConsolidationOptionsFor(options, resolution_m)))
    features.lines.push_back(
        Orient(CellSegmentToFrame(s, grid.geometry()), grid, options.thresholds));
  return features;
}

}  // namespace fleetmap::aggregator
