#include "aggregator/line_features.h"

namespace fleetmap::aggregator {

core::Status LineFeatureOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(thresholds.Validate());
  if (!(strong_log_odds > core::ProbabilityToLogOdds(thresholds.occupied_probability)))
    return core::InvalidArgument("lines.strong_log_odds must lie above the occupied threshold");
  FLEETMAP_RETURN_IF_ERROR(hough.Validate());
  return consolidation.Validate();
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
  FLEETMAP_ASSIGN_OR_RETURN(raw, DetectHoughSegments(features.edges, options.hough));
  features.raw_segments = static_cast<int>(raw.size());
  for (const LineSegment& s : ConsolidateSegments(raw, features.edges, options.consolidation))
    features.lines.push_back(
        Orient(CellSegmentToFrame(s, grid.geometry()), grid, options.thresholds));
  return features;
}

}  // namespace fleetmap::aggregator
