#include "aggregator/alignment/cell_alignment.h"

#include <algorithm>
#include <cmath>

#include "aggregator/alignment/alignment.h"
#include "aggregator/alignment/alignment_steps.h"
#include "aggregator/alignment/overlap_search.h"

namespace fleetmap::aggregator {
namespace {

// The search's window: 2 * n + 1 translations each way, 2 * turns + 1 turns.
struct Window {
  int n = 0, turns = 0;
  double step_m = 0.0, turn_step_rad = 0.0;
  int side() const { return 2 * n + 1; }
  size_t Index(int it, int ix, int iy) const {
    return (static_cast<size_t>(it + turns) * side() + (iy + n)) * side() + (ix + n);
  }
  // Turn and translation of a pose of the window.
  core::Pose2 Correction(const Eigen::Vector2d& pivot, double turn_rad, double x, double y) const {
    return Translation({x, y}) * RotationAbout(pivot, turn_rad);
  }
};

double Score(const StaticMapFeatures& f, const std::vector<Eigen::Vector2d>& placed,
             const core::Pose2& correction) {
  return OverlapScoreAt(f, PlacePoints(placed, correction), Eigen::Vector2d::Zero(),
                        OverlapScore::kSurfaceField);
}

// Whether the window's score at (it, ix, iy) is at least each neighbour's.
bool LocalPeak(const Window& w, const std::vector<double>& s, int it, int ix, int iy) {
  const double v = s[w.Index(it, ix, iy)];
  for (int dt = -1; dt <= 1; ++dt)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int t = it + dt, x = ix + dx, y = iy + dy;
        if ((dt || dx || dy) && std::abs(t) <= w.turns && std::abs(x) <= w.n &&
            std::abs(y) <= w.n && s[w.Index(t, x, y)] > v)
          return false;
      }
  return true;
}

}  // namespace

const char* CellAlignmentUseName(CellAlignmentUse use) {
  switch (use) {
    case CellAlignmentUse::kOff:
      return "off";
    case CellAlignmentUse::kWhereLinesFail:
      return "where_lines_fail";
    case CellAlignmentUse::kFirst:
      return "first";
  }
  return "unknown";
}

core::Result<CellAlignmentUse> ParseCellAlignmentUse(const std::string& name) {
  for (CellAlignmentUse use :
       {CellAlignmentUse::kOff, CellAlignmentUse::kWhereLinesFail, CellAlignmentUse::kFirst})
    if (name == CellAlignmentUseName(use)) return use;
  return core::InvalidArgument("unknown cell alignment use '" + name +
                               "' (known: off, where_lines_fail, first)");
}

core::Status CellAlignmentOptions::Validate() const {
  if (!(range_m > 0 && range_m <= 5.0))
    return core::InvalidArgument("cell_alignment.range_m must be in (0, 5]");
  if (!(range_rad >= 0 && range_rad <= M_PI / 4))
    return core::InvalidArgument("cell_alignment.range_rad must be in [0, pi/4]");
  if (!(step_m > 0 && step_m <= range_m))
    return core::InvalidArgument("cell_alignment.step_m must be in (0, range_m]");
  if (max_points < 10) return core::InvalidArgument("cell_alignment.max_points must be >= 10");
  if (!(rival_separation_m > 0) || !(rival_separation_rad > 0))
    return core::InvalidArgument("cell_alignment.rival_separation_* must be > 0");
  if (!(lines_min_relative_score >= 0 && lines_min_relative_score <= 1))
    return core::InvalidArgument("cell_alignment.lines_min_relative_score must be in [0, 1]");
  return core::OkStatus();
}

CellAlignment AlignCells(const StaticMapFeatures& f,
                         const std::vector<Eigen::Vector2d>& points_in_temp,
                         const core::Pose2& anchor, const CellAlignmentOptions& o) {
  CellAlignment r;
  if (points_in_temp.empty()) return r;
  const Eigen::Vector2d pivot = anchor.translation();
  const std::vector<Eigen::Vector2d> all = PlacePoints(points_in_temp, anchor);
  const std::vector<Eigen::Vector2d> some = Subsample(all, o.max_points);
  double reach_m = 1.0;  // the farthest point from the pivot: a turn's lever
  for (const Eigen::Vector2d& p : all) reach_m = std::max(reach_m, (p - pivot).norm());

  Window w;
  w.step_m = std::max(o.step_m, f.geometry().resolution_m());
  w.n = static_cast<int>(std::ceil(o.range_m / w.step_m));
  // At most 32 turns each way: a temporary map 100 m across would otherwise ask for hundreds.
  w.turn_step_rad = std::max(w.step_m / reach_m, o.range_rad / 32);
  w.turns = static_cast<int>(std::ceil(o.range_rad / w.turn_step_rad));
  std::vector<double> scores(static_cast<size_t>(2 * w.turns + 1) * w.side() * w.side());
  int best_t = 0, best_x = 0, best_y = 0;
  for (int it = -w.turns; it <= w.turns; ++it) {
    const auto turned = PlacePoints(some, RotationAbout(pivot, it * w.turn_step_rad));
    for (int iy = -w.n; iy <= w.n; ++iy)
      for (int ix = -w.n; ix <= w.n; ++ix) {
        const double s =
            OverlapScoreAt(f, turned, {ix * w.step_m, iy * w.step_m}, OverlapScore::kSurfaceField);
        scores[w.Index(it, ix, iy)] = s;
        // Ties go to the pose nearest the anchor: a flat score keeps it.
        const double best = scores[w.Index(best_t, best_x, best_y)];
        if (s > best || (s == best && std::abs(it) + std::abs(ix) + std::abs(iy) <
                                          std::abs(best_t) + std::abs(best_x) + std::abs(best_y))) {
          best_t = it, best_x = ix, best_y = iy;
        }
      }
  }
  const double step_best = scores[w.Index(best_t, best_x, best_y)];
  const double lowest = *std::min_element(scores.begin(), scores.end());
  double rival = lowest;
  for (int it = -w.turns; it <= w.turns; ++it)
    for (int iy = -w.n; iy <= w.n; ++iy)
      for (int ix = -w.n; ix <= w.n; ++ix) {
        const bool apart =
            std::hypot(ix - best_x, iy - best_y) * w.step_m >= o.rival_separation_m ||
            std::abs(it - best_t) * w.turn_step_rad >= o.rival_separation_rad;
        if (apart && scores[w.Index(it, ix, iy)] > rival && LocalPeak(w, scores, it, ix, iy))
          rival = scores[w.Index(it, ix, iy)];
      }
  r.at_edge = std::abs(best_x) == w.n || std::abs(best_y) == w.n ||
              (w.turns > 0 && std::abs(best_t) == w.turns);
  r.search_best = step_best;
  r.search_lowest = lowest;
  const double rise = step_best - lowest;
  r.distinctness = rise > 0 ? (step_best - rival) / rise : 0.0;

  // Refine: halve the steps, move while a neighbour scores higher.
  double turn = best_t * w.turn_step_rad, x = best_x * w.step_m, y = best_y * w.step_m;
  double score = Score(f, all, w.Correction(pivot, turn, x, y));
  for (double h = 0.5; h >= 0.125; h /= 2) {
    for (bool moved = true; moved;) {
      moved = false;
      const double d[3] = {h * w.turn_step_rad, h * w.step_m, h * w.step_m};
      for (int axis = 0; axis < 3; ++axis)
        for (double sign : {-1.0, 1.0}) {
          double t = turn, px = x, py = y;
          (axis == 0 ? t : axis == 1 ? px : py) += sign * d[axis];
          const double s = Score(f, all, w.Correction(pivot, t, px, py));
          if (s > score) score = s, turn = t, x = px, y = py, moved = true;
        }
    }
  }
  r.correction = w.Correction(pivot, turn, x, y);
  r.score = score;
  r.at_anchor = Score(f, all, core::Pose2());
  return r;
}

double CellScoreAt(const StaticMapFeatures& f, const std::vector<Eigen::Vector2d>& points_in_temp,
                   const core::Pose2& anchor, const core::Pose2& correction,
                   const CellAlignmentOptions& o) {
  const std::vector<Eigen::Vector2d> some =
      Subsample(PlacePoints(points_in_temp, anchor), o.max_points);
  return Score(f, some, correction);
}

}  // namespace fleetmap::aggregator
