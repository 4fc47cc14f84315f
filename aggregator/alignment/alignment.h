// The correcting transformation T{dx, dy, dtheta} of the paper (Sec. 3.4), computed in
// sequence: the angle first (the length-weighted mean angle difference of matched lines),
// then the displacement across the lines (their normal distances after the rotation), then
// the displacement along them (the shift of maximum overlap with the static map).
//
// Two modes, a setting:
//   kPaper: as the paper: one matching, the mean angle, dy along the picture's y axis from
//     the lines whose normals point that way, dx along the picture's x axis by counting
//     temporary cells on occupied static cells at whole-cell shifts.
//   kDominantDirections (ours): the axes are the building's two dominant directions (so a
//     hall drawn at any angle works); only lines of those directions vote, with a weighted
//     median and inlier mean instead of the mean; a direction with enough matched lines
//     across it is solved by lines, the other by a sub-cell search of the smooth surface
//     field; match, rotate, translate are repeated with tighter windows.
#pragma once

#include <string>
#include <vector>

#include "aggregator/alignment/line_matcher.h"
#include "aggregator/alignment/overlap_search.h"
#include "aggregator/alignment/static_features.h"

namespace fleetmap::aggregator {

enum class AlignmentMode { kPaper, kDominantDirections };
// "paper" and "ours", the spelling of settings and command lines.
const char* AlignmentModeName(AlignmentMode mode);
core::Result<AlignmentMode> ParseAlignmentMode(const std::string& name);

struct AlignmentOptions {
  AlignmentMode mode = AlignmentMode::kDominantDirections;
  // The first matching, before any correction: its windows cover the anchor's error.
  LineMatchOptions matching;
  // Ours: the normal window of every later matching, once the first correction is applied.
  double refined_max_normal_offset_m = 0.25;
  int iterations = 3;  // ours: rounds of match, rotate, translate, >= 1
  double family_tolerance_rad = 10.0 * M_PI / 180;  // ours: a line of a dominant direction
  double rotation_inlier_rad = 1.0 * M_PI / 180;    // ours: from the weighted median angle
  double offset_inlier_m = 0.1;                     // ours: from the weighted median offset
  double min_family_length_m = 1.0;  // ours: matched length that fixes the shift across a family
  // Ours: the search along a direction lines leave open. Both modes turn about the anchor,
  // so what is left to find is the anchor's translation error: the range must cover it.
  OverlapSearchOptions overlap;
  double refined_search_range_m = 0.15;  // ours: the search's range after the first round
  // The paper's search: whole cells, occupied-cell count.
  OverlapSearchOptions paper_overlap{OverlapScore::kOccupiedCells, 0.5, 0.05, 0.0};
  int max_search_points = 2000;  // points scored per shift (a deterministic subsample), >= 10
  core::Status Validate() const;
};

struct AlignmentInput {
  std::vector<LineSegment> temp_lines;       // the temporary map's segments, in its frame T
  std::vector<Eigen::Vector2d> temp_points;  // its surface cell centres, in T, metres
  core::Pose2 anchor;                        // T in the static frame, from localization
};

struct AlignmentResult {
  core::Pose2 correction;  // placed = correction * anchor, applied in the static frame
  // The paper's numbers: the rotation, and the anchor's displacement along the mode's axes
  // (the picture's x and y for kPaper; the primary direction and its normal for ours).
  double dtheta_rad = 0.0, dx_m = 0.0, dy_m = 0.0;
  Eigen::Vector2d axis_x = Eigen::Vector2d::UnitX(), axis_y = Eigen::Vector2d::UnitY();
  std::vector<LineSegment> temp_lines_in_map;  // the temporary segments, corrected
  std::vector<LineMatch> matches;              // measured after the correction
  bool shift_by_overlap = false;               // a displacement came from the overlap search
  OverlapPeak overlap;  // that search's first peak, over the whole search range
  int rounds = 0;       // match-rotate-translate rounds run
};

AlignmentResult Align(const AlignmentInput& input, const StaticMapFeatures& features,
                      const AlignmentOptions& options);

// The result of a correction found otherwise (cell_alignment.h): the paper's numbers along the
// building's dominant directions and the lines matched after it.
AlignmentResult WithCorrection(const AlignmentInput& input, const StaticMapFeatures& features,
                               const AlignmentOptions& options, const core::Pose2& correction);

// Every `stride`-th point such that at most `max_points` remain (deterministic).
std::vector<Eigen::Vector2d> Subsample(const std::vector<Eigen::Vector2d>& points, int max_points);

}  // namespace fleetmap::aggregator
