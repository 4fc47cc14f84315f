#include "vehicle_agent/localization/pose_hypotheses.h"

#include <algorithm>
#include <cmath>

#include "vehicle_agent/localization/short_beam.h"

namespace fleetmap::vehicle_agent {

core::Status PoseHypothesesOptions::Validate() const {
  const bool ok = decide_margin > 0 && max_loss_per_scan > 0 && drop_margin >= decide_margin &&
                  std::isfinite(drop_margin) && min_scans >= 1 && min_travel_m >= 0 &&
                  fit_step_m > 0 && fit_step_rad > 0 && fit_min_step_m > 0 &&
                  fit_min_step_m <= fit_step_m && same_m >= 0 && same_rad >= 0 &&
                  research_travel_m >= 0 && short_beam_as_m > 0 && short_beam_margin_m > 0 &&
                  max_hypotheses >= 1 && fit_prior_sigma_m > 0 && fit_prior_sigma_rad > 0;
  if (!ok) {
    return core::InvalidArgument(
        "pose hypotheses: decide_margin > 0, max_loss_per_scan > 0, drop_margin >= "
        "decide_margin, min_scans >= 1, min_travel_m >= 0, fit steps > 0 with fit_min_step_m "
        "<= fit_step_m, same_m and same_rad >= 0, research_travel_m >= 0, short_beam_as_m and "
        "short_beam_margin_m > 0, max_hypotheses >= 1, fit_prior_sigma_m and "
        "fit_prior_sigma_rad > 0");
  }
  return core::OkStatus();
}

core::Pose2 PoseHypotheses::Fit(const core::Pose2& start, const LikelihoodField& field,
                                const std::vector<Eigen::Vector2f>& endpoints) const {
  if (endpoints.empty()) return start;
  // The fit's objective: the mean log-likelihood per end point, less a Gaussian prior around
  // where the odometry put the pose. Along an aisle or a corridor the scan alone cannot place
  // the vehicle, and a fit without the prior slides a few cm per scan, whichever way a
  // ragged wall happens to favour.
  const double per_point = 1.0 / static_cast<double>(endpoints.size());
  const auto objective = [&](const core::Pose2& p) {
    const double dx = (p.x_m - start.x_m) / options_.fit_prior_sigma_m;
    const double dy = (p.y_m - start.y_m) / options_.fit_prior_sigma_m;
    const double dt =
        core::NormalizeAngle(p.theta_rad - start.theta_rad) / options_.fit_prior_sigma_rad;
    return field.LogLikelihood(endpoints, p) * per_point - 0.5 * (dx * dx + dy * dy + dt * dt);
  };
  core::Pose2 pose = start;
  double best = objective(pose);
  double step_m = options_.fit_step_m, step_rad = options_.fit_step_rad;
  // Each level moves at most a few steps: a fit follows the pose, it does not wander off.
  constexpr int kMovesPerLevel = 4;
  while (step_m >= options_.fit_min_step_m) {
    for (int move = 0; move < kMovesPerLevel; ++move) {
      core::Pose2 chosen = pose;
      bool moved = false;
      for (const core::Pose2& d : {core::Pose2(step_m, 0, 0), core::Pose2(-step_m, 0, 0),
                                   core::Pose2(0, step_m, 0), core::Pose2(0, -step_m, 0),
                                   core::Pose2(0, 0, step_rad), core::Pose2(0, 0, -step_rad)}) {
        const core::Pose2 candidate(pose.x_m + d.x_m, pose.y_m + d.y_m,
                                    core::NormalizeAngle(pose.theta_rad + d.theta_rad));
        const double score = objective(candidate);
        if (score > best) {
          best = score;
          chosen = candidate;
          moved = true;
        }
      }
      if (!moved) break;
      pose = chosen;
    }
    step_m *= 0.5;
    step_rad *= 0.5;
  }
  return pose;
}

double PoseHypotheses::Evidence(const core::Pose2& base_in_map, const HypothesisScan& scan) const {
  if (scan.endpoints_in_base.empty()) return 0.0;
  const double short_log_p = scan.field.LogProbabilityOfDistance(options_.short_beam_as_m);
  const core::Pose2 scanner_in_map = base_in_map * scan.scanner_in_base;
  const Eigen::Vector2d scanner(scanner_in_map.x_m, scanner_in_map.y_m);
  double sum = 0.0;
  for (const Eigen::Vector2f& p : scan.endpoints_in_base) {
    const Eigen::Vector2d end = base_in_map.Apply(p.cast<double>());
    const double log_p = scan.field.LogLikelihoodAt(end);
    const bool forgiven =
        log_p < short_log_p &&
        EndsShortInFreeSpace(scan.map, scan.field, scanner, end, options_.short_beam_margin_m);
    sum += forgiven ? short_log_p : log_p;
  }
  return sum / static_cast<double>(scan.endpoints_in_base.size());
}

void PoseHypotheses::Start(const std::vector<PoseHypothesis>& seeds, const HypothesisScan& scan) {
  hypotheses_.clear();
  scans_ = 1;
  travel_m_ = 0.0;
  for (const PoseHypothesis& seed : seeds) {
    PoseHypothesis h;
    h.base_in_map = Fit(seed.base_in_map, scan.field, scan.endpoints_in_base);
    h.evidence = Evidence(h.base_in_map, scan) + seed.evidence;
    hypotheses_.push_back(h);
  }
  Prune();
}

void PoseHypotheses::Add(const std::vector<PoseHypothesis>& seeds, const HypothesisScan& scan) {
  if (hypotheses_.empty()) return Start(seeds, scan);
  const double level = best().evidence - options_.decide_margin;
  for (const PoseHypothesis& seed : seeds) {
    PoseHypothesis h;
    h.base_in_map = Fit(seed.base_in_map, scan.field, scan.endpoints_in_base);
    h.evidence = level + seed.evidence;
    hypotheses_.push_back(h);
  }
  Prune();
}

void PoseHypotheses::Update(const core::Pose2& odometry_delta, const HypothesisScan& scan) {
  if (hypotheses_.empty() || scan.endpoints_in_base.empty()) return;
  ++scans_;
  travel_m_ += std::hypot(odometry_delta.x_m, odometry_delta.y_m) +
               std::abs(odometry_delta.theta_rad) * 1.0;  // 1 m per rad
  std::vector<double> scan_log_p(hypotheses_.size());
  for (size_t i = 0; i < hypotheses_.size(); ++i) {
    PoseHypothesis& h = hypotheses_[i];
    h.base_in_map = Fit(h.base_in_map * odometry_delta, scan.field, scan.endpoints_in_base);
    scan_log_p[i] = Evidence(h.base_in_map, scan);
  }
  const double best_log_p = *std::max_element(scan_log_p.begin(), scan_log_p.end());
  for (size_t i = 0; i < hypotheses_.size(); ++i)
    hypotheses_[i].evidence += std::max(scan_log_p[i], best_log_p - options_.max_loss_per_scan);
  Prune();
}

// Best first; the far behind dropped; of two that met, the better kept.
void PoseHypotheses::Prune() {
  std::stable_sort(
      hypotheses_.begin(), hypotheses_.end(),
      [](const PoseHypothesis& a, const PoseHypothesis& b) { return a.evidence > b.evidence; });
  std::vector<PoseHypothesis> kept;
  for (const PoseHypothesis& h : hypotheses_) {
    if (!kept.empty() && h.evidence < kept.front().evidence - options_.drop_margin) break;
    const bool met = std::any_of(kept.begin(), kept.end(), [&](const PoseHypothesis& k) {
      const core::Pose2 d = core::Between(k.base_in_map, h.base_in_map);
      return std::hypot(d.x_m, d.y_m) < options_.same_m &&
             std::abs(d.theta_rad) < options_.same_rad;
    });
    if (!met) kept.push_back(h);
    if (static_cast<int>(kept.size()) == options_.max_hypotheses) break;
  }
  hypotheses_ = std::move(kept);
}

bool PoseHypotheses::decided() const {
  if (hypotheses_.size() == 1) return true;
  return hypotheses_.size() > 1 && scans_ >= options_.min_scans &&
         travel_m_ >= options_.min_travel_m &&
         hypotheses_[0].evidence - hypotheses_[1].evidence >= options_.decide_margin;
}

Eigen::Matrix3d PoseHypotheses::Covariance(const Eigen::Vector3d& floor) const {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  if (hypotheses_.empty()) return Eigen::Matrix3d(floor.asDiagonal());
  const core::Pose2& b = best().base_in_map;
  for (const PoseHypothesis& h : hypotheses_) {
    const Eigen::Vector3d d(h.base_in_map.x_m - b.x_m, h.base_in_map.y_m - b.y_m,
                            core::NormalizeAngle(h.base_in_map.theta_rad - b.theta_rad));
    c += d * d.transpose();
  }
  c /= static_cast<double>(hypotheses_.size());
  for (int i = 0; i < 3; ++i) c(i, i) = std::max(c(i, i), floor(i));
  return c;
}

}  // namespace fleetmap::vehicle_agent
