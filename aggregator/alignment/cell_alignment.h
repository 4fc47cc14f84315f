// Alignment by cells, where lines are few or mislead: an office of short walls and furniture,
// a hall of curved walls, clutter. The temporary map's surface cells are placed at every pose
// of a window around the vehicle's anchor (a correlative search, as in Olson's real-time
// correlative scan matching) and scored by the static map's smooth surface field; the best
// pose is refined to a fraction of a cell. Cells that changed (a pallet that was not in the
// static map) score nothing at every pose near the anchor, so the fit is decided by what did
// not change. Its answer is trusted only where its peak stands out from any rival pose.
#pragma once

#include <string>
#include <vector>

#include "aggregator/alignment/static_features.h"
#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::aggregator {

// When the aggregator aligns by cells (aggregator.h): never, where the lines' correction is
// rejected, or first (the lines where the cells' is rejected).
enum class CellAlignmentUse { kOff, kWhereLinesFail, kFirst };
// "off", "where_lines_fail", "first": the spelling of settings.
const char* CellAlignmentUseName(CellAlignmentUse use);
core::Result<CellAlignmentUse> ParseCellAlignmentUse(const std::string& name);

struct CellAlignmentOptions {
  CellAlignmentUse use = CellAlignmentUse::kFirst;
  // The window around the anchor, each way: what a localized vehicle's anchor can be off by.
  double range_m = 0.3;
  double range_rad = 3.0 * M_PI / 180;
  // The search's translation step, metres > 0; the static map's cell is used where it is
  // larger (the surface field is a cell wide). Turn steps move the farthest point as much
  // (at most 32 turns each way).
  double step_m = 0.03;
  int max_points = 600;  // scored per pose in the search; the refinement uses all, >= 10
  // Another local peak at least this far away (metres, or radians of turn) is a rival.
  double rival_separation_m = 0.15;
  double rival_separation_rad = 1.5 * M_PI / 180;
  // Where the cells find another pose almost as good, the lines may choose between the
  // poses that fit, never a pose that fits worse: their pose must score at least this far
  // from the window's lowest score to its best (a rival within 1 - min_distinctness of the
  // best scores at least that much), else the map is ambiguous. 0 takes any lines' pose.
  double lines_min_relative_score = 0.7;
  core::Status Validate() const;
};

struct CellAlignment {
  core::Pose2 correction;  // placed = correction * anchor, as AlignmentResult's
  double score = 0.0;      // mean surface field of the points at the best pose
  double at_anchor = 0.0;  // ... with no correction
  // Of the search's poses: (best - rival) / (best - lowest), the rival the best other local
  // peak (OverlapPeak::Distinctness): 1 for a single peak, near 0 when another pose fits
  // almost as well (a corridor with nothing across it), 0 for a flat score.
  double distinctness = 0.0;
  bool at_edge = false;  // the best pose lies on the window's border
  // The search's best and lowest scores (on the subsampled points, before refinement).
  double search_best = 0.0;
  double search_lowest = 0.0;
  // Where `score_at_pose` (CellScoreAt) lies from the lowest (0) to the best (1).
  double Relative(double score_at_pose) const {
    const double rise = search_best - search_lowest;
    return rise > 0 ? (score_at_pose - search_lowest) / rise : 0.0;
  }
};

// `points_in_temp`: the temporary map's surface cell centres in its frame T; `anchor`: T in
// the static frame.
CellAlignment AlignCells(const StaticMapFeatures& features,
                         const std::vector<Eigen::Vector2d>& points_in_temp,
                         const core::Pose2& anchor, const CellAlignmentOptions& options);

// The search's score of the pose `correction * anchor`, on the same subsample of points, to
// judge another method's pose against the search's (CellAlignment::Relative).
double CellScoreAt(const StaticMapFeatures& features,
                   const std::vector<Eigen::Vector2d>& points_in_temp, const core::Pose2& anchor,
                   const core::Pose2& correction, const CellAlignmentOptions& options);

}  // namespace fleetmap::aggregator
