#include "vehicle_agent/pose_hypotheses.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::vehicle_agent {

core::Status PoseHypothesesOptions::Validate() const {
  const bool ok = decide_margin > 0 && drop_margin >= decide_margin && std::isfinite(drop_margin) &&
                  min_scans >= 1 && min_travel_m >= 0 && fit_step_m > 0 && fit_step_rad > 0 &&
                  fit_min_step_m > 0 && fit_min_step_m <= fit_step_m && same_m >= 0 &&
                  same_rad >= 0;
  if (!ok) {
    return core::InvalidArgument(
        "pose hypotheses: decide_margin > 0, drop_margin >= decide_margin, min_scans >= 1, "
        "min_travel_m >= 0, "
        "fit steps > 0 with fit_min_step_m <= fit_step_m, same_m and same_rad >= 0");
  }
  return core::OkStatus();
}

core::Pose2 PoseHypotheses::Fit(const core::Pose2& start, const LikelihoodField& field,
                                const std::vector<Eigen::Vector2f>& endpoints,
                                double& mean_log_p) const {
  core::Pose2 pose = start;
  double best = field.LogLikelihood(endpoints, pose);
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
        const double score = field.LogLikelihood(endpoints, candidate);
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
  mean_log_p = endpoints.empty() ? 0.0 : best / static_cast<double>(endpoints.size());
  return pose;
}

void PoseHypotheses::Start(const std::vector<PoseHypothesis>& seeds, const LikelihoodField& field,
                           const std::vector<Eigen::Vector2f>& endpoints_in_base) {
  hypotheses_.clear();
  scans_ = 1;
  travel_m_ = 0.0;
  for (const PoseHypothesis& seed : seeds) {
    PoseHypothesis h;
    h.base_in_map = Fit(seed.base_in_map, field, endpoints_in_base, h.evidence);
    h.evidence += seed.evidence;
    hypotheses_.push_back(h);
  }
  Prune();
}

void PoseHypotheses::Update(const core::Pose2& odometry_delta, const LikelihoodField& field,
                            const std::vector<Eigen::Vector2f>& endpoints_in_base) {
  if (hypotheses_.empty() || endpoints_in_base.empty()) return;
  ++scans_;
  travel_m_ += std::hypot(odometry_delta.x_m, odometry_delta.y_m) +
               std::abs(odometry_delta.theta_rad) * 1.0;  // 1 m per rad
  for (PoseHypothesis& h : hypotheses_) {
    double mean_log_p = 0.0;
    h.base_in_map = Fit(h.base_in_map * odometry_delta, field, endpoints_in_base, mean_log_p);
    h.evidence += mean_log_p;
  }
  Prune();
}

// Best first; the far behind dropped; of two that met, the better kept.
void PoseHypotheses::Prune() {
  std::sort(
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
