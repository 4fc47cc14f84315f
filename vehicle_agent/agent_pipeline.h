// The vehicle's per-scan pipeline, the paper's Fig. 2 on board: localize on the current map,
// compute W_avg and the divergence d(t), and while d(t) says the map no longer explains the
// laser, build a temporary map; hand each closed temporary map to the caller (the agent
// process sends it to the aggregator). Free of LCM and I/O: time and data come in, results
// go out, so a replay is repeatable.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vehicle_agent/candidate_watch.h"
#include "vehicle_agent/divergence.h"
#include "vehicle_agent/localization/localizer.h"
#include "vehicle_agent/mapping/temp_map_builder.h"

namespace fleetmap::vehicle_agent {

struct AgentPipelineOptions {
  std::string vehicle_id = "vehicle";
  core::Pose2 scanner_in_base;  // mounting pose of the laser scanner
  LocalizerOptions localizer;
  DivergenceOptions divergence;
  TempMapBuilderOptions builder;  // the map's resolution is the current map's
  // Sequence number of the first temporary map, >= 1. The agent process continues its
  // numbering across restarts, so that the aggregator never takes a new map for a duplicate.
  int32_t first_sequence = 1;
  // A temporary map being built when no scan came for longer than this (the agent stalled,
  // the scanner dropped out) closes at its last scan, and the change goes on in a new map
  // anchored where localization puts the vehicle now: the matcher would have to bridge the
  // whole gap blind (1 m at 1 m/s), and one scan put in the wrong place spoils the map.
  // Seconds, > 0; scans come every 0.02-0.1 s.
  double max_scan_gap_s = 1.0;
  // Watching the fleet map's candidates (SetCandidates): what counts as passing through and
  // ending at one, and how well localized the vehicle must be for its beams to be trusted
  // with single cells: the larger standard deviation of its position, metres (a cell is 0.02
  // to 0.10 m; beyond this a beam may be judged against the wrong cell).
  CandidateWatchOptions candidate_watch;
  double candidate_watch_max_sigma_m = 0.05;
  core::Status Validate() const;
};

struct AgentStep {
  core::PoseEstimate pose;  // localized pose (never NaN)
  LocalizerStats localization;
  DivergenceSample divergence;              // the paper's Fig. 3 sample of this scan
  std::optional<core::TempMap> closed_map;  // a temporary map this scan completed
  bool building = false;                    // a temporary map is being built
  bool well_localized = false;              // good enough to anchor a map (covariance, not lost)
};

struct AgentCounters {
  int64_t scans = 0;
  int64_t temp_maps_started = 0;
  int64_t temp_maps_closed = 0;
  int64_t temp_maps_split = 0;    // closed for size, time, a clock step or a scan gap while the
                                  // change went on
  int64_t temp_maps_dropped = 0;  // being built when the vehicle found it was elsewhere: drawn
                                  // from a wrong pose, never sent
};

class AgentPipeline {
 public:
  explicit AgentPipeline(const AgentPipelineOptions& options);

  // The current map (static map plus merged changes) and its version; swapped in without
  // stopping: the particles, the divergence averages and a map being built all carry on.
  core::Status SetMap(const core::OccupancyGrid& map, int32_t version);
  // A new version that differs from the one in use only inside `changed`: the same result as
  // SetMap, at a cost that grows with the change rather than the building.
  core::Status UpdateMap(const core::OccupancyGrid& map, int32_t version,
                         const core::CellWindow& changed);
  core::Status InitializeAt(const core::Pose2& pose_in_map, const Eigen::Matrix3d& covariance);
  core::Status AddExternalPose(const core::PoseEstimate& pose_in_map);

  // Every odometry sample, in order: the localizer composes each increment, and the next scan
  // uses the most recent sample.
  void AddOdometry(const core::OdometrySample& odom);
  AgentStep AddScan(const core::LaserScan& scan);
  // The fleet map's candidates, cell indices of the current map (replacing the last set).
  void SetCandidates(const std::vector<int64_t>& cells);
  // The candidates this vehicle's scans saw free since the last call (CandidateWatch).
  CandidatesSeenFree TakeSeenFree();
  // The candidates this vehicle's scans saw held since the last call (CandidateWatch).
  CandidatesHeld TakeHeld();
  // Closes a temporary map being built (at shutdown).
  std::optional<core::TempMap> Flush(double stamp_s);

  const AgentCounters& counters() const { return counters_; }
  const Localizer& localizer() const { return localizer_; }
  const AgentPipelineOptions& options() const { return options_; }

 private:
  void StartMap(double stamp_s, const core::PoseEstimate& anchor);
  void WatchCandidates(const core::LaserScan& scan, const core::PoseEstimate& pose);
  // Position sigma within candidate_watch_max_sigma_m: beams may be judged against single
  // cells, and a map opened at start-up may be anchored.
  bool WellLocalized(const core::PoseEstimate& pose) const;

  AgentPipelineOptions options_;
  Localizer localizer_;
  DivergenceDetector divergence_;
  TempMapBuilder builder_;
  core::OdometrySample odom_;
  // The localizer's clean odometry where the temporary map last moved on: at its anchor, then
  // at each scan it took. The next scan is placed by the motion since.
  core::Pose2 clean_odom_at_builder_;
  std::optional<double> last_scan_stamp_s_;  // of the last valid scan
  int32_t next_sequence_ = 1;
  // A map was split while the change goes on (closed for its time or area, or at a scan gap):
  // the next one starts at the next scan that comes (after a gap, the scan at hand), anchored
  // at that scan's localized pose, as every map is (its frame T is the vehicle there).
  bool continue_change_ = false;
  AgentCounters counters_;
  std::optional<CandidateWatch> watch_;  // from the first map on
  std::vector<int64_t> candidates_;      // the last set given
};

}  // namespace fleetmap::vehicle_agent
