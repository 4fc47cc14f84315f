// The two dominant directions of a building's lines. The paper measures its corrections
// along the picture's axes (Sec. 3.4), which suits halls drawn axis-aligned; a hall at any
// angle in its map has its own two directions, found here as the two strongest peaks of the
// length-weighted histogram of line directions (undirected, so modulo pi).
#pragma once

#include <vector>

#include "aggregator/alignment/line_segment.h"
#include "core/result.h"

namespace fleetmap::aggregator {

struct DominantDirectionOptions {
  double bin_rad = M_PI / 180;                    // histogram bin width, (0, pi/36]
  double smoothing_rad = 2.0 * M_PI / 180;        // peaks are summed over +- this, >= 0
  double min_separation_rad = 30.0 * M_PI / 180;  // the second peak lies this far from the first
  core::Status Validate() const;
};

struct DominantDirections {
  double primary_rad = 0.0;         // direction angle of the most line length, [0, pi)
  double secondary_rad = M_PI / 2;  // the strongest direction at least min_separation away
  double primary_length = 0.0;      // line length within the smoothing window of each peak
  double secondary_length = 0.0;
  // Unit vectors along each direction, and the normal of the primary one.
  Eigen::Vector2d primary() const;
  Eigen::Vector2d secondary() const;
};

// Lengths in the lines' units. With no lines: x and y axes.
DominantDirections FindDominantDirections(const std::vector<LineSegment>& lines,
                                          const DominantDirectionOptions& options = {});

}  // namespace fleetmap::aggregator
