// Line features of an occupancy grid, in the frame the grid's geometry is expressed in
// (metres): edge pixels, their Hough segments, one consolidated segment per edge. The same
// extraction serves the static map (once, on its surface cells) and every temporary map (in
// its own frame T, on its cells with repeated hits: surface_image.h says why they differ).
#pragma once

#include <vector>

#include "aggregator/alignment/hough_lines.h"
#include "aggregator/alignment/line_consolidation.h"
#include "aggregator/alignment/line_segment.h"
#include "aggregator/alignment/surface_image.h"
#include "core/map/occupancy_grid.h"

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
  // Lengths in the building, metres, the same at any resolution (used on a grid as cells,
  // HoughOptionsFor and ConsolidationOptionsFor):
  double min_length_m = 0.5;       // shorter segments are no line (Hough and consolidated)
  double min_vote_length_m = 0.6;  // a Hough line needs this much of edge pixels on it
  double max_hough_gap_m = 0.2;    // edge pixels this far apart still make one Hough segment
  double max_join_gap_m = 0.3;     // segments of one edge this far apart join; a door does not
  // Of the grid's quantisation, cells, the same at any resolution: an edge of strong cells is
  // about two cells thick, a static surface row one. End points this close to a group's line
  // join it, and pixels this close take part in its refit.
  double max_join_distance_cells = 2.0;
  double fit_band_cells = 1.5;
  double theta_step_rad = M_PI / 360;            // the Hough accumulator's angle resolution
  double max_angle_diff_rad = 4.0 * M_PI / 180;  // segments of one edge differ by at most this
  int min_fit_pixels = 6;                        // fewer: a group keeps its Hough geometry
  core::Status Validate() const;
};

// The options for a static map: edges on its surface cells, which form rows one cell thick,
// so a group and its refit stay within a cell of its line and the two faces of a thin wall
// (two cells apart) stay two lines.
inline LineFeatureOptions StaticLineOptions() {
  LineFeatureOptions options;
  options.source = EdgeSource::kSurfaceCells;
  options.max_join_distance_cells = 1.0;
  options.fit_band_cells = 0.8;
  return options;
}

// The picture-level options for a grid of `resolution_m`: the lengths in whole pixels (at
// least 3 votes, at least 2 cells long, gaps of at least one cell), the accumulator's
// distance resolution one cell. At 0.05 m: 12 votes, 10 cells long, gaps of 4 and 6 cells.
HoughOptions HoughOptionsFor(const LineFeatureOptions& options, double resolution_m);
ConsolidationOptions ConsolidationOptionsFor(const LineFeatureOptions& options,
                                             double resolution_m);

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
