// Line segments of a binary picture by OpenCV's probabilistic Hough transform (HoughLinesP,
// the paper's reference [6]). OpenCV stays behind this header; its exceptions become a Status.
#pragma once

#include <vector>

#include "aggregator/alignment/line_segment.h"
#include "aggregator/alignment/surface_image.h"
#include "core/result.h"

namespace fleetmap::aggregator {

// In pixels of the picture; for a grid, HoughOptionsFor (line_features.h) sets them from
// lengths in metres.
struct HoughOptions {
  double rho_cells = 1.0;              // distance resolution of the accumulator, cells, > 0
  double theta_step_rad = M_PI / 360;  // angle resolution of the accumulator, (0, pi/8]
  int min_votes = 12;                  // accumulator votes a line needs, >= 1
  double min_length_cells = 10.0;      // shorter segments are dropped
  double max_gap_cells = 4.0;          // set pixels this far apart still join one segment, >= 0
  core::Status Validate() const;
};

// Segments in pixel-centre coordinates: pixel (x, y) is the point (x + 0.5, y + 0.5), i.e. the
// cell coordinates of the grid the picture was made from. Sorted as OpenCV returns them.
core::Result<std::vector<LineSegment>> DetectHoughSegments(const BinaryImage& image,
                                                           const HoughOptions& options);

}  // namespace fleetmap::aggregator
