// Monte Carlo localization (Probabilistic Robotics, ch. 8; as in AMCL): particles predicted
// by the odometry motion model, weighted by the likelihood field, resampled with the
// low-variance sampler when the effective sample size drops, their number adapted by KLD
// sampling. The map can be swapped for a new version at any time without stopping or losing
// the particles. Every scan also yields W_avg, the paper's eq. (1), at the estimated pose.
//
// Frames: `pose_in_map` is the vehicle base in the static map frame; odometry is the base in
// the drifting odometry frame; `scanner_in_base` is the scanner mount.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/odometry.h"
#include "core/scan.h"
#include "vehicle_agent/localization/external_pose_track.h"
#include "vehicle_agent/localization/global_search.h"
#include "vehicle_agent/localization/input_guard.h"
#include "vehicle_agent/localization/likelihood_field.h"
#include "vehicle_agent/localization/localizer_options.h"
#include "vehicle_agent/localization/lost_watch.h"
#include "vehicle_agent/localization/odometry_path.h"
#include "vehicle_agent/localization/particle_set.h"

namespace fleetmap::vehicle_agent {

// Running totals since construction: what was dropped or repaired, and how often.
struct LocalizerCounters {
  int64_t scans = 0;                  // Update() calls
  int64_t scans_invalid = 0;          // header failed LaserScan::Validate or mount not finite
  int64_t scans_out_of_order = 0;     // stamp not after the last accepted scan
  int64_t scans_without_returns = 0;  // accepted, but no usable beam: prediction only
  int64_t scan_layout_changes = 0;    // beam count or angles differ from the scan before
  int64_t beams_invalid = 0;          // NaN, -inf, zero, negative, below range_min_m
  int64_t odometry_invalid = 0;       // non-finite field
  int64_t odometry_out_of_order = 0;  // stamp before the last sample
  int64_t odometry_jumps = 0;         // increment above max_odometry_step_*: dropped
  int64_t clock_steps_back = 0;       // scans or odometry whose clock was set back: applied
  int64_t weight_resets = 0;          // every particle impossible: weights made uniform
  int64_t filter_updates = 0;
  int64_t resamplings = 0;
  int64_t external_poses_dropped = 0;  // invalid, out of order or ignored by the mode
  int64_t external_reinits = 0;        // particles re-initialised around an external pose
  int64_t global_searches = 0;         // scans searched for over the whole map
  int64_t lost_searches = 0;           // ... of them because the vehicle was lost
  int64_t relocalizations = 0;         // ... after which the particles restarted elsewhere
};

struct LocalizerStats {
  int particles = 0;
  double effective_sample_size = 0.0;  // 1 / sum(w^2) after this update's weighting
  // W_avg (eq. 1) of this scan at the estimated pose: the per-beam geometric mean of
  // options.w_avg_model. NaN when the scan was dropped or had no usable beam, or no map.
  double w_avg = std::numeric_limits<double>::quiet_NaN();
  int beams_scored = 0;         // end points per particle in this update
  bool filter_updated = false;  // prediction and measurement ran for this scan
  bool resampled = false;
  bool external = false;  // the estimate is the external pose carried forward (kPassThrough)
  // Share of this update's end points near a mapped obstacle at the estimate; NaN without a
  // filter update. Below options.lost_explained_share for lost_after_s: lost.
  double explained_share = std::numeric_limits<double>::quiet_NaN();
  bool lost = false;         // found elsewhere by a search, until a scan is explained again
  bool relocalized = false;  // the particles restarted around a search's poses at this scan
  LocalizerCounters counters;
};

struct LocalizerResult {
  core::PoseEstimate estimate;  // never NaN
  LocalizerStats stats;
};

class Localizer {
 public:
  // `options` must pass Validate() (an assert).
  explicit Localizer(const LocalizerOptions& options);

  // Uses `map` from now on; the particles stay where they are. The first map also initialises
  // the filter (options.initial_pose_mode). An empty map is refused and the old one kept.
  core::Status SetMap(const core::OccupancyGrid& map, int32_t version);
  // The same for a version that differs from the map in use only inside `changed` (a
  // merge's tiles): the scan models recompute only what that can change, so a new version
  // does not stall the scan loop for the whole building. SetMap when there is no map yet or
  // the geometry differs.
  core::Status UpdateMap(const core::OccupancyGrid& map, int32_t version,
                         const core::CellWindow& changed);
  // Restarts the particles around a pose (an operator's or configured initial pose).
  core::Status InitializeAt(const core::Pose2& pose_in_map, const Eigen::Matrix3d& covariance);
  // Global localization: the next scan is searched for over the whole map and the particles
  // restart around the poses that fit it (or over the free cells when none does).
  core::Status InitializeGlobal();
  // A pose from the vehicle's own localization, taken to refer to the time of the last
  // Update (at most one scan period off; it is carried forward by odometry from there).
  // Used per options.external_pose_mode; refused when invalid or older than the last one.
  core::Status AddExternalPose(const core::PoseEstimate& pose_in_map);

  // Every odometry sample as it arrives, so that the increments between two scans the caller
  // had to skip (it fell behind) are composed one by one: taken at once they would be one
  // step of metres, refused as a jump, and the motion lost. Bad samples are dropped and counted.
  void AddOdometry(const core::OdometrySample& odom) { TrackOdometry(odom); }
  // One scan with the odometry sample closest to it (adding a sample AddOdometry already had
  // is harmless: a zero step). Bad input is dropped and counted (see LocalizerCounters); the
  // returned pose is always finite.
  LocalizerResult Update(const core::OdometrySample& odom, const core::LaserScan& scan,
                         const core::Pose2& scanner_in_base);

  bool initialized() const { return initialized_; }
  int32_t map_version() const { return map_version_; }
  const ParticleSet& particles() const { return particles_; }
  // The poses a global search found, while they are followed (empty otherwise).
  const PoseHypotheses& hypotheses() const { return hypotheses_; }
  const LocalizerCounters& counters() const { return counters_; }
  // What the filter has learnt of the odometry's scale: the vehicle's distance per odometry
  // distance (odometry_scale.h), 1 until the first resampling.
  double odometry_scale() const { return odometry_scale_; }
  const LocalizerOptions& options() const { return options_; }
  // The odometry pose with every refused increment cut out (OdometryTracker).
  const core::Pose2& clean_odometry() const { return odometry_.clean_pose(); }

 private:
  // The filter (localizer.cc).
  void TrackOdometry(const core::OdometrySample& odom);
  bool AcceptScan(const core::LaserScan& scan, const core::Pose2& scanner_in_base);
  bool PassingThrough(double stamp_s);
  bool FilterDue() const;
  void FilterUpdate(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                    LocalizerStats& stats);
  void Predict();
  void PredictStep(const core::Pose2& delta);
  void Weigh(LocalizerStats& stats);
  void Resample();
  bool FuseOrReinitialize();
  void Restart(ParticleSet particles);
  void ExtrapolateOdometry(double scan_stamp_s);
  core::Pose2 OdomAtScan() const { return odometry_.clean_pose() * odom_to_scan_; }
  core::Pose2 CurrentPose() const;
  core::PoseEstimate Estimate(bool external);
  core::Pose2 ExternalNow() const { return external_.Now(OdomAtScan()); }

  // Global localization (localizer_global.cc): searches of the whole map, at the start and
  // when lost, and the poses they found followed until one leads.
  // The global search for `scan` and the restart around what it found.
  void StartFromGlobalSearch(const core::LaserScan& scan, const core::Pose2& scanner_in_base);
  // While the hypotheses are undecided and the last search may have left poses out: the scan
  // searched for again each hypotheses.research_travel_m of driving, the poses found added.
  void SearchAgainIfAmbiguous(const core::LaserScan& scan, const core::Pose2& scanner_in_base);
  // The search returned as many poses as it may: others may fit as well.
  bool Full(const std::vector<GlobalCandidate>& found) const;
  // Lost: the scans unexplained for lost_after_s; then searched for, and the particles moved
  // when the search finds a clearly better pose.
  void CheckLost(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                 LocalizerStats& stats);
  const GlobalSearch& SearchOfCurrentMap();
  std::vector<Eigen::Vector2f> SearchPoints(const core::LaserScan& scan,
                                            const core::Pose2& scanner_in_base) const;
  // Follows the poses found (PoseHypotheses) from this scan on; `held`: the estimate, as one
  // more with a head start.
  void RestartAround(const std::vector<GlobalCandidate>& found, const core::LaserScan& scan,
                     const core::Pose2& scanner_in_base,
                     const std::optional<core::Pose2>& held = std::nullopt);
  void TrackHypotheses(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                       LocalizerStats& stats);
  // The particles start at the hypothesis that won; until then the estimate is the best one.
  void FollowHypotheses();

  const LocalizerOptions options_;
  LikelihoodField field_;
  std::unique_ptr<ScanLikelihood> beam_model_;  // null unless w_avg_model is kBeamModel
  core::OccupancyGrid map_;
  int32_t map_version_ = -1;
  bool has_map_ = false;
  bool initialized_ = false;
  bool force_update_ = false;
  std::mt19937 rng_;
  ParticleSet particles_;
  PoseMoments moments_;  // of the particles at the last filter update
  // The particles' weighted mean odometry scale at the last resampling: where a new set's
  // scales are drawn around (odometry_scale.h).
  double odometry_scale_ = 1.0;
  core::Pose2 clean_odom_at_update_;  // the tracker's clean odometry then
  OdometryTracker odometry_;
  OdometryPath path_;         // the clean odometry's way since clean_odom_at_update_
  core::Pose2 odom_to_scan_;  // the last odometry sample carried to the scan's stamp
  ScanGate scans_;
  ExternalPoseTrack external_;
  core::PoseEstimate last_estimate_;        // the last finite one
  std::vector<Eigen::Vector2f> endpoints_;  // scratch
  std::vector<double> log_weights_;         // scratch
  LocalizerCounters counters_;
  bool global_pending_ = false;                  // InitializeGlobal waits for a scan
  std::unique_ptr<GlobalSearch> global_search_;  // of map_version_, built when first needed
  int32_t global_search_version_ = -1;
  PoseHypotheses hypotheses_;  // active from a global search until one pose leads
  // The last search returned max_candidates poses (others may fit as well), after this much
  // of the hypotheses' travel.
  bool search_full_ = false;
  double searched_at_travel_m_ = 0.0;
  LostWatch lost_;
};

}  // namespace fleetmap::vehicle_agent
