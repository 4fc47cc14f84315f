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
    features.lines.push_back(CellSegmentToFrame(s, grid.geometry()));
  return features;
}

}  // namespace fleetmap::aggregator
