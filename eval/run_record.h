// What one run of a pipeline produced, in the form the evaluation scores: the current map at
// the end and every cell any version of it held occupied, the merges with where each
// temporary map was placed, the divergence and pose traces. Filled in-process by a pipeline
// or read back from a recorded run.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/map/occupancy_grid.h"

namespace fleetmap::eval {

// One row of the paper's Tables 1 and 2.
struct LineMatchRow {
  int temp_line_id = 0;
  int static_line_id = 0;
  double distance_diff_px = 0.0;
  double angle_diff_deg = 0.0;
};

struct MergeRecord {
  std::string vehicle_id;
  int tempmap_seq = 0;
  double closed_s = 0.0;  // the temporary map was closed on the vehicle
  double merged_s = 0.0;  // the change was in the current map
  bool accepted = false;
  std::string reason;
  core::Pose2 placed_origin;  // the temporary map's origin as placed (anchor + correction)
  core::Pose2 true_origin;    // where it truly lies (from the simulator's ground truth)
  // Where the vehicle placed it (its anchor, before the aggregator's correction): compared
  // with placed_origin, whether the alignment made the placement better or worse.
  core::Pose2 anchor_origin;
  // How far the vehicle's builder drifted within the map (tempmap_drift.h); NaN where the run
  // does not know (perfect maps, a recorded run).
  double drift_m = std::nan("");
  double drift_deg = std::nan("");
  // How the anchor's true error (x, y, theta in the static frame) compares with the
  // covariance the vehicle sent with the map: e' C^-1 e, on average 3 and below 7.81 for 95 %
  // of maps where the localizer knows how sure it is. NaN where no covariance travelled.
  double anchor_nees = std::nan("");
  // The aggregator's view of its correction (AlignmentConfidence): how far it moved the anchor
  // against the anchor's covariance (squared Mahalanobis, NaN without one), and how much more
  // of the map the static map explains after it than at the anchor. NaN where not aligned.
  double correction_mahalanobis_sq = std::nan("");
  double fit_gain = std::nan("");
  std::vector<LineMatchRow> lines;
  int cells_added = 0;
  int cells_removed = 0;
};

struct DivergenceSample {
  std::string vehicle_id;
  double t_s = 0.0;
  double w_avg = 0.0, w_slow = 0.0, w_fast = 0.0, d = 0.0;
  bool building = false;  // a temporary map is being built
};

struct PoseSample {
  std::string vehicle_id;
  double t_s = 0.0;
  core::Pose2 estimated;
  core::Pose2 truth;
};

struct RunRecord {
  std::string pipeline;  // which pipeline made this run ("oracle", "agents", ...)
  core::OccupancyGrid final_map;
  std::vector<uint8_t> ever_occupied;  // per cell: occupied in some version of the map
  // Per cell: a candidate there was dropped because a vehicle saw it free (empty: the run
  // does not tell, as a recorded one does not).
  std::vector<uint8_t> dropped_seen_free;
  std::vector<MergeRecord> merges;
  std::vector<DivergenceSample> divergence;
  std::vector<PoseSample> poses;

  // Call with every version of the current map (the first is the static map).
  void RecordVersion(const core::OccupancyGrid& current_map);
  // Call with the cells of every drop of candidates seen free (and once with none, so that a
  // run without drops tells that it had none).
  void RecordSeenFreeDrops(const std::vector<int64_t>& cells);
};

}  // namespace fleetmap::eval
