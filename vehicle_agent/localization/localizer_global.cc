// The Localizer's global localization (localizer.h): the scan searched for over the whole map
// (GlobalSearch) at the start and when the vehicle is lost, and the poses found followed scan
// by scan (PoseHypotheses) until one leads and the particles start there.
#include <algorithm>

#include "core/pose_covariance.h"
#include "vehicle_agent/localization/localizer.h"
#include "vehicle_agent/localization/particle_init.h"
#include "vehicle_agent/localization/scan_endpoints.h"

namespace fleetmap::vehicle_agent {

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
      core::DiagonalCovariance(options_.global_sigma_xy_m, options_.global_sigma_theta_rad);
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
    Restart(SampleAroundPose(best, core::DiagonalCovariance(xy, theta), options_.kld.max_particles,
                             rng_));
    return;
  }
  moments_.mean = best;
  moments_.covariance = hypotheses_.Covariance(Eigen::Vector3d(xy * xy, xy * xy, theta * theta));
}

void Localizer::CheckLost(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                          LocalizerStats& stats) {
  const double now_s = scans_.last_stamp_s();
  const bool search_due = lost_.SearchDue(stats.explained_share, now_s);
  stats.lost = lost_.lost();
  if (!search_due) return;
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
    lost_.NothingBetter(now_s);
    return;
  }
  ++counters_.relocalizations;
  lost_.FoundElsewhere();
  stats.lost = stats.relocalized = true;
  RestartAround(found, scan, scanner_in_base, CurrentPose());
}

}  // namespace fleetmap::vehicle_agent
