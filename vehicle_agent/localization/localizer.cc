#include "vehicle_agent/localization/localizer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/pose_covariance.h"
#include "vehicle_agent/localization/particle_init.h"
#include "vehicle_agent/localization/resampling.h"
#include "vehicle_agent/localization/scan_endpoints.h"

namespace fleetmap::vehicle_agent {

Localizer::Localizer(const LocalizerOptions& options)
    : options_(options),
      field_(options.likelihood_field),
      rng_(options.seed),
      odometry_(options.max_odometry_step_m, options.max_odometry_step_rad,
                options.max_odometry_speed_mps, options.max_odometry_yaw_rate_radps),
      path_(options.prediction_step_m, options.prediction_step_rad),
      external_(options),
      hypotheses_(options.hypotheses),
      lost_(options.lost_after_s, options.lost_explained_share, options.lost_max_search_period_s) {
  assert(options.Validate().ok());
  if (options.w_avg_model == WAvgModel::kBeamModel) beam_model_ = MakeBeamModel(options.beam_model);
  moments_.mean = options.initial_pose_in_map;
  moments_.covariance =
      core::DiagonalCovariance(options.initial_sigma_xy_m, options.initial_sigma_theta_rad);
  last_estimate_.pose_in_map = moments_.mean;
  last_estimate_.covariance = moments_.covariance;
}

core::Status Localizer::SetMap(const core::OccupancyGrid& map, int32_t version) {
  if (map.geometry().num_cells() == 0 ||
      static_cast<int64_t>(map.cells().size()) != map.geometry().num_cells()) {
    return core::InvalidArgument("localizer: refusing an empty map as version " +
                                 std::to_string(version));
  }
  field_.SetMap(map);
  if (beam_model_) beam_model_->SetMap(map);
  map_ = map;
  map_version_ = version;
  has_map_ = true;
  if (initialized_) return core::OkStatus();
  if (options_.initial_pose_mode == InitialPoseMode::kGlobal) return InitializeGlobal();
  return InitializeAt(
      options_.initial_pose_in_map,
      core::DiagonalCovariance(options_.initial_sigma_xy_m, options_.initial_sigma_theta_rad));
}

core::Status Localizer::UpdateMap(const core::OccupancyGrid& map, int32_t version,
                                  const core::CellWindow& changed) {
  if (!has_map_ || !(map.geometry() == map_.geometry()) ||
      static_cast<int64_t>(map.cells().size()) != map.geometry().num_cells())
    return SetMap(map, version);
  field_.UpdateMap(map, changed);
  if (beam_model_) beam_model_->UpdateMap(map, changed);
  // The window's rows only: a copy of the whole grid would be most of the cost on a large map.
  const core::CellWindow w = map.geometry().Grown(changed, 0);
  const int width = map.geometry().width();
  for (int y = w.y0; y < w.y0 + w.height; ++y) {
    const size_t row = size_t(y) * width + w.x0;
    std::copy_n(map.cells().begin() + row, w.width, map_.mutable_cells().begin() + row);
  }
  map_version_ = version;
  return core::OkStatus();
}

core::Status Localizer::InitializeAt(const core::Pose2& pose_in_map,
                                     const Eigen::Matrix3d& covariance) {
  if (!pose_in_map.IsFinite()) return core::InvalidArgument("initial pose is not finite");
  FLEETMAP_RETURN_IF_ERROR(core::ValidatePoseCovariance(covariance));
  global_pending_ = false;
  Restart(SampleAroundPose(pose_in_map, covariance, options_.kld.max_particles, rng_));
  return core::OkStatus();
}

void Localizer::Restart(ParticleSet particles) {
  particles_ = std::move(particles);
  // The vehicle's wheels did not change: drawn around what the filter had learnt of them.
  DrawOdometryScales(particles_, odometry_scale_, options_.odometry_scale, rng_);
  initialized_ = true;
  force_update_ = true;
  moments_ = ComputeMoments(particles_);
  clean_odom_at_update_ = OdomAtScan();
  path_.Restart(clean_odom_at_update_);
  lost_.Restart();
  hypotheses_.Clear();
}

core::Status Localizer::AddExternalPose(const core::PoseEstimate& pose_in_map) {
  const core::Status status = external_.Add(pose_in_map, OdomAtScan());
  if (!status.ok()) ++counters_.external_poses_dropped;
  return status;
}

LocalizerResult Localizer::Update(const core::OdometrySample& odom, const core::LaserScan& scan,
                                  const core::Pose2& scanner_in_base) {
  ++counters_.scans;
  LocalizerStats stats;
  TrackOdometry(odom);
  const bool scan_ok = AcceptScan(scan, scanner_in_base);
  ExtrapolateOdometry(scans_.last_stamp_s());
  stats.external = PassingThrough(scans_.last_stamp_s());
  if (!stats.external && scan_ok && has_map_ && initialized_ && global_pending_)
    StartFromGlobalSearch(scan, scanner_in_base);
  const bool due = !stats.external && scan_ok && has_map_ && initialized_ && FilterDue();
  if (due && hypotheses_.active()) {
    TrackHypotheses(scan, scanner_in_base, stats);
    stats.lost = lost_.lost();
  } else if (due) {
    FilterUpdate(scan, scanner_in_base, stats);
    CheckLost(scan, scanner_in_base, stats);
  } else {
    stats.lost = lost_.lost();
  }
  LocalizerResult result{Estimate(stats.external), stats};
  if (scan_ok) {
    const ScanLikelihood& w_avg_model = beam_model_ ? *beam_model_ : field_;
    result.stats.w_avg =
        w_avg_model.MeanBeamLikelihood(scan, result.estimate.pose_in_map * scanner_in_base);
  }
  result.stats.particles = static_cast<int>(particles_.size());
  if (!stats.filter_updated) result.stats.effective_sample_size = EffectiveSampleSize(particles_);
  result.stats.counters = counters_;
  return result;
}

core::PoseEstimate Localizer::Estimate(bool external) {
  core::PoseEstimate e;
  e.stamp_s = scans_.last_stamp_s();
  e.pose_in_map = external ? ExternalNow() : CurrentPose();
  e.covariance = external ? external_.Covariance() : moments_.covariance;
  e.map_version = map_version_;
  // A last line of defence: whatever went wrong upstream, the pose handed on is finite.
  if (!e.pose_in_map.IsFinite() || !e.covariance.allFinite()) return last_estimate_;
  last_estimate_ = e;
  return e;
}

void Localizer::TrackOdometry(const core::OdometrySample& odom) {
  switch (odometry_.Add(odom)) {
    case OdometryTracker::Outcome::kApplied:
      path_.Add(odometry_.clean_pose());
      break;
    case OdometryTracker::Outcome::kInvalid:
      ++counters_.odometry_invalid;
      break;
    case OdometryTracker::Outcome::kOutOfOrder:
      ++counters_.odometry_out_of_order;
      break;
    case OdometryTracker::Outcome::kJump:
      ++counters_.odometry_jumps;
      break;
    case OdometryTracker::Outcome::kClockStep:
      ++counters_.clock_steps_back;
      path_.Add(odometry_.clean_pose());
      break;
    case OdometryTracker::Outcome::kFirst:
      break;
  }
}

void Localizer::ExtrapolateOdometry(double scan_stamp_s) {
  odom_to_scan_ = core::Pose2();
  if (!odometry_.has_sample() || !scans_.has_scan()) return;
  const core::OdometrySample& o = odometry_.last();
  const double limit = options_.max_odometry_extrapolation_s;
  const double dt = std::clamp(scan_stamp_s - o.stamp_s, -limit, limit);
  const double turn = o.omega_radps * dt, travel = o.v_mps * dt;
  const core::Pose2 step(travel * std::cos(0.5 * turn), travel * std::sin(0.5 * turn), turn);
  if (step.IsFinite() && std::hypot(step.x_m, step.y_m) <= options_.max_odometry_step_m)
    odom_to_scan_ = step;
}

bool Localizer::AcceptScan(const core::LaserScan& scan, const core::Pose2& scanner_in_base) {
  switch (scans_.Check(scan, scanner_in_base)) {
    case ScanGate::Outcome::kInvalid:
      ++counters_.scans_invalid;
      return false;
    case ScanGate::Outcome::kOutOfOrder:
      ++counters_.scans_out_of_order;
      return false;
    case ScanGate::Outcome::kClockStep:
      ++counters_.clock_steps_back;
      break;
    case ScanGate::Outcome::kAccepted:
      break;
  }
  if (scans_.layout_changed()) ++counters_.scan_layout_changes;
  for (size_t i = 0; i < scan.size(); ++i)
    counters_.beams_invalid += ClassifyBeam(scan, i, scan.range_max_m) == BeamReading::kInvalid;
  return true;
}

bool Localizer::PassingThrough(double stamp_s) {
  const ExternalPoseTrack::Pass pass = external_.PassThrough(stamp_s);
  if (pass == ExternalPoseTrack::Pass::kLapsed) {
    // MCL takes over from where the external pose left off.
    ++counters_.external_reinits;
    Restart(
        SampleAroundPose(ExternalNow(), external_.Covariance(), options_.kld.max_particles, rng_));
  }
  return pass == ExternalPoseTrack::Pass::kPassing;
}

bool Localizer::FilterDue() const {
  const core::Pose2 moved = core::Between(clean_odom_at_update_, OdomAtScan());
  return force_update_ || std::hypot(moved.x_m, moved.y_m) >= options_.update_min_translation_m ||
         std::abs(moved.theta_rad) >= options_.update_min_rotation_rad;
}

void Localizer::FilterUpdate(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                             LocalizerStats& stats) {
  force_update_ = false;
  Predict();
  if (external_.fuse_due() && FuseOrReinitialize()) {
    return;  // restarted around the external pose; the next scan weighs the new particles
  }
  ScanEndpoints(scan, scanner_in_base, options_.max_beams, options_.likelihood_field.max_range_m,
                endpoints_);
  if (endpoints_.empty()) {
    ++counters_.scans_without_returns;
  } else {
    Weigh(stats);
    if (stats.effective_sample_size <
        options_.resample_min_neff_ratio * static_cast<double>(particles_.size())) {
      Resample();
      stats.resampled = true;
    }
  }
  moments_ = ComputeMoments(particles_);
  if (!endpoints_.empty()) {
    stats.explained_share = ExplainedShare(map_, field_, endpoints_, moments_.mean, scanner_in_base,
                                           options_.lost_explained_distance_m);
  }
  ++counters_.filter_updates;
  stats.filter_updated = true;
  stats.beams_scored = static_cast<int>(endpoints_.size());
}

void Localizer::Predict() {
  core::Pose2 from = clean_odom_at_update_;
  for (const core::Pose2& waypoint : path_.waypoints()) {
    PredictStep(core::Between(from, waypoint));
    from = waypoint;
  }
  PredictStep(core::Between(from, OdomAtScan()));
  clean_odom_at_update_ = OdomAtScan();
  path_.Restart(clean_odom_at_update_);
}

void Localizer::PredictStep(const core::Pose2& delta) {
  const double translation_m = std::hypot(delta.x_m, delta.y_m);
  for (Particle& p : particles_) {
    p.pose = SampleMotionModelOdometry(p.pose, ScaledIncrement(delta, p.odometry_scale),
                                       options_.motion, rng_);
    p.odometry_scale =
        WalkOdometryScale(p.odometry_scale, translation_m, options_.odometry_scale, rng_);
  }
}

void Localizer::Weigh(LocalizerStats& stats) {
  const bool fuse = external_.TakeFuse();
  const core::Pose2 external = fuse ? ExternalNow() : core::Pose2();
  const Eigen::Matrix3d information = core::InformationMatrix(external_.Covariance());
  log_weights_.resize(particles_.size());
  double max_log_weight = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < particles_.size(); ++i) {
    double lw = field_.LogLikelihood(endpoints_, particles_[i].pose);
    if (fuse) {
      const Eigen::Vector3d d = core::PoseDifference(particles_[i].pose, external);
      lw -= 0.5 * d.dot(information * d);  // the external pose as one more measurement
    }
    log_weights_[i] = lw;
    max_log_weight = std::max(max_log_weight, lw);
  }
  for (size_t i = 0; i < particles_.size(); ++i)
    particles_[i].weight *= std::exp(log_weights_[i] - max_log_weight);
  if (!NormalizeWeights(particles_)) ++counters_.weight_resets;
  stats.effective_sample_size = EffectiveSampleSize(particles_);
}

void Localizer::Resample() {
  odometry_scale_ = MeanOdometryScale(particles_);
  ParticleSet resampled = LowVarianceResample(particles_, particles_.size(), rng_);
  const size_t target = static_cast<size_t>(
      KldParticleCount(CountOccupiedBins(resampled, options_.kld), options_.kld));
  if (target != resampled.size()) resampled = LowVarianceResample(particles_, target, rng_);
  particles_ = std::move(resampled);
  ++counters_.resamplings;
}

bool Localizer::FuseOrReinitialize() {
  const PoseMoments m = ComputeMoments(particles_);
  const core::Pose2 external = ExternalNow();
  const double gate = options_.external_reinit_mahalanobis;
  if (core::SquaredMahalanobis(core::PoseDifference(m.mean, external),
                               m.covariance + external_.Covariance()) <= gate * gate) {
    return false;
  }
  external_.TakeFuse();  // the restart around it is its fusion: not weighed in again
  ++counters_.external_reinits;
  Restart(SampleAroundPose(external, external_.Covariance(), options_.kld.max_particles, rng_));
  return true;
}

core::Pose2 Localizer::CurrentPose() const {
  return moments_.mean * core::Between(clean_odom_at_update_, OdomAtScan());
}

}  // namespace fleetmap::vehicle_agent
