#include "vehicle_agent/localization/particle_set.h"

#include <cassert>
#include <cmath>

namespace fleetmap::vehicle_agent {

bool NormalizeWeights(ParticleSet& particles) {
  double sum = 0.0;
  for (const Particle& p : particles) sum += p.weight;
  const bool ok = sum > 0.0 && std::isfinite(sum);
  const double uniform = particles.empty() ? 0.0 : 1.0 / static_cast<double>(particles.size());
  for (Particle& p : particles) p.weight = ok ? p.weight / sum : uniform;
  return ok;
}

double EffectiveSampleSize(const ParticleSet& particles) {
  double sum_sq = 0.0;
  for (const Particle& p : particles) sum_sq += p.weight * p.weight;
  return sum_sq > 0.0 ? 1.0 / sum_sq : 0.0;
}

PoseMoments ComputeMoments(const ParticleSet& particles) {
  assert(!particles.empty());
  double x = 0.0, y = 0.0, c = 0.0, s = 0.0;
  for (const Particle& p : particles) {
    x += p.weight * p.pose.x_m;
    y += p.weight * p.pose.y_m;
    c += p.weight * std::cos(p.pose.theta_rad);
    s += p.weight * std::sin(p.pose.theta_rad);
  }
  PoseMoments m;
  m.mean = core::Pose2(x, y, std::atan2(s, c));
  for (const Particle& p : particles) {
    const Eigen::Vector3d d(p.pose.x_m - x, p.pose.y_m - y,
                            core::NormalizeAngle(p.pose.theta_rad - m.mean.theta_rad));
    m.covariance += p.weight * d * d.transpose();
  }
  return m;
}

}  // namespace fleetmap::vehicle_agent
