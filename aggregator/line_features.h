// Line features of an occupancy grid, in the frame the grid's geometry is expressed in
// (metres): edge pixels, their Hough segments, one consolidated segment per edge. The same
// extraction serves the static map (once, on its surface cells) and every temporary map (in
// its own frame T, on its cells with repeated hits: surface_image.h says why they differ).
#pragma once

#include <vector>

#include "aggregator/hough_lines.h"
#include "aggregator/line_consolidation.h"
#include "aggregator/line_segment.h"
#include "aggregator/surface_image.h"
#include "core/occupancy_grid.h"

namespace fleetmap::aggregator {

enum class EdgeSource {
  kSurfaceCells,  // occupied cells next to free ones (static maps)
  kStrongCells,   // cells with log-odds of at least strong_log_odds (temporary maps)
};

struct LineFeatureOptions {
  EdgeSource source = EdgeSource::kStrongCells;
  // kStrongCells: 3.0 is two clean hits (2.2 each) or more; a single stray return is not an
  // edge. Above the occupied threshold.
  float strong_log_odds = 3.0f;
  core::OccupancyThresholds thresholds;  // which cells are occupied and free
  HoughOptions hough;
  ConsolidationOptions consolidation;
  core::Status Validate() const;
};

// The options for a static map: edges on its surface cells, which form rows one cell thick,
// so a group and its refit stay within a cell of its line and the two faces of a thin wall
// (two cells apart) stay two lines.
inline LineFeatureOptions StaticLineOptions() {
  LineFeatureOptions options;
  options.source = EdgeSource::kSurfaceCells;
  options.consolidation.max_normal_distance_cells = 1.0;
  options.consolidation.fit_band_cells = 0.8;
  return options;
}

struct LineFeatures {
  std::vector<LineSegment> lines;  // metres, in the grid geometry's parent frame, longest first
  BinaryImage edges;               // the edge pixels the lines were found in
  int raw_segments = 0;            // Hough segments before consolidation
};

core::Result<LineFeatures> ExtractLineFeatures(const core::OccupancyGrid& grid,
                                               const LineFeatureOptions& options);

// Cell coordinates of a grid (cell (x, y) spans [x, x+1) x [y, y+1)) to the frame the grid's
// geometry is expressed in, metres.
LineSegment CellSegmentToFrame(const LineSegment& cells, const core::GridGeometry& geometry);

}  // namespace fleetmap::aggregator
