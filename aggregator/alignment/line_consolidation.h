// One segment per edge. The Hough transform returns several segments for one edge (its
// width, sensor noise, the accumulator's quantisation: the paper, Sec. 3.4); these are
// grouped when they are nearly parallel, close along the normal and overlapping or close
// along the line, and each group is refitted by total least squares on the edge points
// near it, which gives its r and theta to a fraction of a cell.
#pragma once

#include <vector>

#include "aggregator/alignment/line_segment.h"
#include "aggregator/alignment/surface_image.h"
#include "core/result.h"

namespace fleetmap::aggregator {

// In pixels of the picture; for a grid, ConsolidationOptionsFor (line_features.h) sets them
// from lengths in metres.
struct ConsolidationOptions {
  double max_angle_diff_rad = 4.0 * M_PI / 180;  // segments of one edge differ by at most this
  double max_normal_distance_cells = 2.0;  // end points this close to the group's line join it
  double max_gap_cells = 6.0;              // along the line; a door's width keeps walls apart
  double fit_band_cells = 1.5;     // pixels this close to a group's line take part in its refit
  double min_length_cells = 10.0;  // shorter consolidated segments are dropped
  int min_fit_pixels = 6;          // fewer pixels: the group keeps its Hough geometry
  core::Status Validate() const;
};

// `raw` in cell coordinates of `image` (cell (x, y) spans [x, x+1) x [y, y+1), as
// DetectHoughSegments returns them); the refit uses the centres of the set pixels. The
// result is in the same coordinates, longest first.
std::vector<LineSegment> ConsolidateSegments(const std::vector<LineSegment>& raw,
                                             const BinaryImage& image,
                                             const ConsolidationOptions& options);

}  // namespace fleetmap::aggregator
