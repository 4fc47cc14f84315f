#include "vehicle_agent/localizer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "vehicle_agent/particle_init.h"
#include "vehicle_agent/resampling.h"
#include "vehicle_agent/scan_endpoints.h"
#include "vehicle_agent/short_beam.h"

namespace fleetmap::vehicle_agent {
namespace {

Eigen::Matrix3d DiagonalCovariance(double sigma_xy_m, double sigma_theta_rad) {
  return Eigen::Vector3d(sigma_xy_m * sigma_xy_m, sigma_xy_m * sigma_xy_m,
                         sigma_theta_rad * sigma_theta_rad)
      .asDiagonal();
}

Eigen::Vector3d PoseDifference(const core::Pose2& a, const core::Pose2& b) {
  return {a.x_m - b.x_m, a.y_m - b.y_m, core::NormalizeAngle(a.theta_rad - b.theta_rad)};
}

// cov^-1, with a tiny regularisation so that a singular covariance stays usable.
Eigen::Matrix3d Information(const Eigen::Matrix3d& cov) {
  return (cov + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
}

double SquaredMahalanobis(const Eigen::Vector3d& d, const Eigen::Matrix3d& cov) {
  return d.dot(Information(cov) * d);
}

}  // namespace

Localizer::Localizer(const LocalizerOptions& options)
    : options_(options),
      field_(options.likelihood_field),
      rng_(options.seed),
      odometry_(options.max_odometry_step_m, options.max_odometry_step_rad,
                options.max_odometry_speed_mps, options.max_odometry_yaw_rate_radps),
      path_(options.prediction_step_m, options.prediction_step_rad),
      hypotheses_(options.hypotheses) {
  assert(options.Validate().ok());
  if (options.w_avg_model == WAvgModel::kBeamModel) beam_model_ = MakeBeamModel(options.beam_model);
  moments_.mean = options.initial_pose_in_map;
  moments_.covariance =
      DiagonalCovariance(options.initial_sigma_xy_m, options.initial_sigma_theta_rad);
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
      DiagonalCovariance(options_.initial_sigma_xy_m, options_.initial_sigma_theta_rad));
}

core::Status Localizer::InitializeAt(const core::Pose2& pose_in_map,
                                     const Eigen::Matrix3d& covariance) {
  if (!pose_in_map.IsFinite()) return core::InvalidArgument("initial pose is not finite");
  FLEETMAP_RETURN_IF_ERROR(ValidatePoseCovariance(covariance));
  global_pending_ = false;
  Restart(SampleAroundPose(pose_in_map, covariance, options_.kld.max_particles, rng_));
  return core::OkStatus();
}

core::Status Localizer::InitializeGlobal() {
  if (!has_map_) return core::FailedPrecondition("global initialisation needs a map");
  ParticleSet particles = SampleFreeSpace(map_, options_.kld.max_particles, rng_);
  if (particles.empty()) return core::FailedPrecondition("the map has no free cell");
  // Spread until the first scan tells where to look.
  Restart(std::move(particles));
  global_pending_ = true;
  return core::OkStatus();
}

const GlobalSearch& Localizer::SearchOfCurrentMap() {
  if (!global_search_ || global_search_version_ != map_version_) {
    global_search_ = std::make_unique<GlobalSearch>(map_, options_.global_search);
    global_search_version_ = map_version_;
  }
  return *global_search_;
}

std::vector<Eigen::Vector2f> Localizer::SearchPoints(const core::LaserScan& scan,
                                                     const core::Pose2& scanner_in_base) const {
  std::vector<Eigen::Vector2f> points;
  ScanEndpoints(scan, scanner_in_base, static_cast<int>(scan.ranges_m.size()),
                options_.likelihood_field.max_range_m, points);
  return points;
}

void Localizer::StartFromGlobalSearch(const core::LaserScan& scan,
                                      const core::Pose2& scanner_in_base) {
  global_pending_ = false;
  ++counters_.global_searches;
  const std::vector<GlobalCandidate> found =
      SearchOfCurrentMap().Search(SearchPoints(scan, scanner_in_base));
  if (found.empty()) return;  // the particles stay spread over the free space
  RestartAround(found, scan, scanner_in_base);
}

void Localizer::RestartAround(const std::vector<GlobalCandidate>& found,
                              const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                              const std::optional<core::Pose2>& held) {
  const Eigen::Matrix3d around =
      DiagonalCovariance(options_.global_sigma_xy_m, options_.global_sigma_theta_rad);
  const int each = std::max(1, options_.kld.max_particles / static_cast<int>(found.size()));
  ParticleSet particles;
  std::vector<PoseHypothesis> seeds;
  if (held) seeds.push_back({*held, options_.hypotheses.decide_margin});
  for (const GlobalCandidate& c : found) {
    ParticleSet near = SampleAroundPose(c.base_in_map, around, each, rng_);
    particles.insert(particles.end(), near.begin(), near.end());
    seeds.push_back({c.base_in_map, 0.0});
  }
  for (Particle& p : particles) p.weight = 1.0 / particles.size();
  Restart(std::move(particles));
  ScanEndpoints(scan, scanner_in_base, options_.max_beams, options_.likelihood_field.max_range_m,
                endpoints_);
  hypotheses_.Start(seeds, {map_, field_, endpoints_, scanner_in_base});
  search_full_ = Full(found);
  searched_at_travel_m_ = 0.0;
  FollowHypotheses();
}

bool Localizer::Full(const std::vector<GlobalCandidate>& found) const {
  return static_cast<int>(found.size()) >= options_.global_search.max_candidates;
}

void Localizer::SearchAgainIfAmbiguous(const core::LaserScan& scan,
                                       const core::Pose2& scanner_in_base) {
  const double every_m = options_.hypotheses.research_travel_m;
  if (!search_full_ || every_m <= 0 || !hypotheses_.active() || hypotheses_.decided() ||
      hypotheses_.travel_m() < searched_at_travel_m_ + every_m)
    return;
  ++counters_.global_searches;
  const std::vector<GlobalCandidate> found =
      SearchOfCurrentMap().Search(SearchPoints(scan, scanner_in_base));
  search_full_ = Full(found);
  searched_at_travel_m_ = hypotheses_.travel_m();
  std::vector<PoseHypothesis> seeds;
  for (const GlobalCandidate& c : found) seeds.push_back({c.base_in_map, 0.0});
  hypotheses_.Add(seeds, {map_, field_, endpoints_, scanner_in_base});
}

void Localizer::TrackHypotheses(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                                LocalizerStats& stats) {
  force_update_ = false;
  const core::Pose2 moved = core::Between(clean_odom_at_update_, OdomAtScan());
  clean_odom_at_update_ = OdomAtScan();
  path_.Restart(clean_odom_at_update_);
  ScanEndpoints(scan, scanner_in_base, options_.max_beams, options_.likelihood_field.max_range_m,
                endpoints_);
  hypotheses_.Update(moved, {map_, field_, endpoints_, scanner_in_base});
  SearchAgainIfAmbiguous(scan, scanner_in_base);
  stats.beams_scored = static_cast<int>(endpoints_.size());
  FollowHypotheses();
}

void Localizer::FollowHypotheses() {
  if (!hypotheses_.active()) return;
  const core::Pose2 best = hypotheses_.best().base_in_map;
  const double xy = options_.global_sigma_xy_m, theta = options_.global_sigma_theta_rad;
  if (hypotheses_.decided()) {
    Restart(
        SampleAroundPose(best, DiagonalCovariance(xy, theta), options_.kld.max_particles, rng_));
    return;
  }
  moments_.mean = best;
  moments_.covariance = hypotheses_.Covariance(Eigen::Vector3d(xy * xy, xy * xy, theta * theta));
}

// An end point is explained when it lies near a mapped obstacle, or when its beam ended short
// of one in space the map holds free (a pallet, a person, a vehicle that is not in the map:
// the building's changes, not a wrong pose). Only beams that went through a mapped obstacle,
// or ended far from any in unknown space, speak against the pose.
double Localizer::ExplainedShare(const core::Pose2& base_in_map,
                                 const core::Pose2& scanner_in_base) const {
  if (endpoints_.empty()) return std::numeric_limits<double>::quiet_NaN();
  const core::Pose2 scanner_in_map = base_in_map * scanner_in_base;
  const Eigen::Vector2d origin(scanner_in_map.x_m, scanner_in_map.y_m);
  int explained = 0;
  for (const Eigen::Vector2f& p : endpoints_) {
    const Eigen::Vector2d end = base_in_map.Apply(p.cast<double>());
    explained +=
        field_.DistanceAt(end) <= options_.lost_explained_distance_m ||
        EndsShortInFreeSpace(map_, field_, origin, end, options_.lost_explained_distance_m);
  }
  return static_cast<double>(explained) / endpoints_.size();
}

void Localizer::CheckLost(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                          LocalizerStats& stats) {
  stats.lost = lost_;
  if (options_.lost_after_s <= 0 || std::isnan(stats.explained_share)) return;
  const double now_s = scans_.last_stamp_s();
  if (stats.explained_share >= options_.lost_explained_share) {
    stats.lost = lost_ = false;
    unexplained_since_s_ = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  if (std::isnan(unexplained_since_s_)) {
    unexplained_since_s_ = now_s;
    lost_search_period_s_ = options_.lost_after_s;
    next_lost_search_s_ = now_s + lost_search_period_s_;
  }
  if (now_s < next_lost_search_s_) return;
  ++counters_.global_searches;
  ++counters_.lost_searches;
  const GlobalSearch& search = SearchOfCurrentMap();
  const std::vector<Eigen::Vector2f> points = SearchPoints(scan, scanner_in_base);
  const std::vector<GlobalCandidate> found = search.Search(points);
  // A map that changed around a well-placed vehicle explains less everywhere: only a pose that
  // fits clearly better than the estimate moves the particles, and only when the scan tells
  // places apart (a vehicle facing a new row of pallets sees one flat face, which fits as well
  // at every wall: seen on the hall, 32 candidates all scoring 0.80). Otherwise look again
  // later, and less often while nothing better turns up.
  constexpr double kAlikeScore = 0.02;
  const bool alike = Full(found) && found.front().score - found.back().score < kAlikeScore;
  if (found.empty() || alike ||
      found.front().score < search.Score(points, CurrentPose()) + options_.relocalize_margin) {
    lost_search_period_s_ = std::min(2 * lost_search_period_s_, options_.lost_max_search_period_s);
    next_lost_search_s_ = now_s + lost_search_period_s_;
    return;
  }
  ++counters_.relocalizations;
  stats.lost = lost_ = stats.relocalized = true;
  RestartAround(found, scan, scanner_in_base, CurrentPose());
}

void Localizer::Restart(ParticleSet particles) {
  particles_ = std::move(particles);
  initialized_ = true;
  force_update_ = true;
  moments_ = ComputeMoments(particles_);
  clean_odom_at_update_ = OdomAtScan();
  path_.Restart(clean_odom_at_update_);
  unexplained_since_s_ = std::numeric_limits<double>::quiet_NaN();  // judged from here on
  hypotheses_.Clear();
}

core::Status Localizer::AddExternalPose(const core::PoseEstimate& pose_in_map) {
  core::Status status = pose_in_map.Validate();
  if (status.ok() && has_external_ && pose_in_map.stamp_s < external_.pose.stamp_s)
    status = core::InvalidArgument("external pose older than the previous one");
  if (status.ok() && options_.external_pose_mode == ExternalPoseMode::kIgnore)
    status = core::FailedPrecondition("external poses are ignored (external_pose_mode)");
  if (!status.ok()) {
    ++counters_.external_poses_dropped;
    return status;
  }
  external_ = {pose_in_map, OdomAtScan()};
  has_external_ = external_fresh_ = true;
  external_lapsed_ = false;
  return core::OkStatus();
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
    stats.lost = lost_;
  } else if (due) {
    FilterUpdate(scan, scanner_in_base, stats);
    CheckLost(scan, scanner_in_base, stats);
  } else {
    stats.lost = lost_;
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
  e.covariance = external ? ExternalCovariance() : moments_.covariance;
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
  if (options_.external_pose_mode != ExternalPoseMode::kPassThrough || !has_external_) return false;
  if (stamp_s - external_.pose.stamp_s <= options_.external_timeout_s) return true;
  if (!external_lapsed_) {  // MCL takes over from where the external pose left off
    external_lapsed_ = true;
    ++counters_.external_reinits;
    Restart(
        SampleAroundPose(ExternalNow(), ExternalCovariance(), options_.kld.max_particles, rng_));
  }
  return false;
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
  if (options_.external_pose_mode == ExternalPoseMode::kFuse && external_fresh_ &&
      FuseOrReinitialize()) {
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
  if (!endpoints_.empty()) stats.explained_share = ExplainedShare(moments_.mean, scanner_in_base);
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
  for (Particle& p : particles_)
    p.pose = SampleMotionModelOdometry(p.pose, delta, options_.motion, rng_);
}

void Localizer::Weigh(LocalizerStats& stats) {
  const bool fuse = options_.external_pose_mode == ExternalPoseMode::kFuse && external_fresh_;
  external_fresh_ = false;
  const core::Pose2 external = fuse ? ExternalNow() : core::Pose2();
  const Eigen::Matrix3d information = Information(ExternalCovariance());
  log_weights_.resize(particles_.size());
  double max_log_weight = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < particles_.size(); ++i) {
    double lw = field_.LogLikelihood(endpoints_, particles_[i].pose);
    if (fuse) {
      const Eigen::Vector3d d = PoseDifference(particles_[i].pose, external);
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
  if (SquaredMahalanobis(PoseDifference(m.mean, external), m.covariance + ExternalCovariance()) <=
      gate * gate) {
    return false;
  }
  external_fresh_ = false;
  ++counters_.external_reinits;
  Restart(SampleAroundPose(external, ExternalCovariance(), options_.kld.max_particles, rng_));
  return true;
}

core::Pose2 Localizer::CurrentPose() const {
  return moments_.mean * core::Between(clean_odom_at_update_, OdomAtScan());
}

core::Pose2 Localizer::ExternalNow() const {
  return external_.pose.pose_in_map * core::Between(external_.clean_odom, OdomAtScan());
}

Eigen::Matrix3d Localizer::ExternalCovariance() const {
  const Eigen::Matrix3d& c = external_.pose.covariance;
  if (c(0, 0) > 0 && c(1, 1) > 0 && c(2, 2) > 0) return c;
  return DiagonalCovariance(options_.external_sigma_xy_m, options_.external_sigma_theta_rad);
}

}  // namespace fleetmap::vehicle_agent
