// Matches the temporary map's segments (placed in the static frame) to the static map's, as
// the paper does (Sec. 3.4): candidates are static segments of a similar angle (and the same
// facing, when both know theirs: line_segment.h) that the
// normal drawn from the temporary segment's mid point meets within a distance; pairs of
// temporary segments must match pairs of static segments with the same normal distance
// between them (for parallel pairs, whose separation a rigid motion keeps), and among the
// candidates each temporary segment takes the one its pairs agree with, else the nearest.
#pragma once

#include <vector>

#include "aggregator/alignment/line_segment.h"
#include "core/result.h"

namespace fleetmap::aggregator {

struct LineMatchOptions {
  double max_angle_diff_rad = 6.0 * M_PI / 180;  // candidate angle window, (0, pi/4)
  double max_normal_offset_m = 1.0;  // candidate window along the normal from the mid point
  double extent_margin_m = 0.3;    // the normal may meet the static segment this far beyond an end
  double min_temp_length_m = 0.4;  // shorter temporary segments are not matched
  // Pairs: parallel within this angle, and their separations agree within this distance.
  double parallel_tolerance_rad = 3.0 * M_PI / 180;
  double pair_tolerance_m = 0.15;
  bool use_pairs = true;  // false: every temporary segment takes its nearest candidate
  core::Status Validate() const;
};

struct LineMatch {
  int temp_index = 0;    // into the temporary segments
  int static_index = 0;  // into the static segments
  // Turn from the temporary to the static line, [-pi/2, pi/2).
  double angle_diff_rad = 0.0;
  // Shift along `normal` that puts the temporary mid point on the static line.
  double offset_m = 0.0;
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  // the static line's unit normal
  double weight_m = 0.0;                              // the temporary segment's length
  double support_m = 0.0;  // length of other parallel temporary segments whose pairs agree
};

// One match per temporary segment that has a candidate, in temporary-segment order.
std::vector<LineMatch> MatchLines(const std::vector<LineSegment>& temp_in_map,
                                  const std::vector<LineSegment>& static_lines,
                                  const LineMatchOptions& options);

// Recomputes angle difference and offset of each match for moved temporary segments.
void UpdateMatches(const std::vector<LineSegment>& temp_in_map,
                   const std::vector<LineSegment>& static_lines, std::vector<LineMatch>& matches);

}  // namespace fleetmap::aggregator
