#include "vehicle_agent/localization/resampling.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {

ParticleSet LowVarianceResample(const ParticleSet& particles, size_t count, std::mt19937& rng) {
  ParticleSet out;
  if (particles.empty() || count == 0) return out;
  out.reserve(count);
  const double step = 1.0 / static_cast<double>(count);
  const double r = std::uniform_real_distribution<double>(0.0, step)(rng);
  const double weight = step;
  size_t i = 0;
  double cumulative = particles[0].weight;
  for (size_t m = 0; m < count; ++m) {
    const double u = r + static_cast<double>(m) * step;
    while (u > cumulative && i + 1 < particles.size()) cumulative += particles[++i].weight;
    out.push_back(particles[i]);
    out.back().weight = weight;
  }
  return out;
}

core::Status KldOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(min_particles >= 1, "KldOptions.min_particles", min_particles, ">= 1"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(max_particles >= min_particles && max_particles <= 1000000,
                                       "KldOptions.max_particles", max_particles,
                                       ">= min_particles and <= 1000000"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(bin_xy_m > 0 && std::isfinite(bin_xy_m), "KldOptions.bin_xy_m", bin_xy_m, "> 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(bin_theta_rad > 0 && std::isfinite(bin_theta_rad),
                                       "KldOptions.bin_theta_rad", bin_theta_rad, "> 0"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(epsilon > 0 && std::isfinite(epsilon), "KldOptions.epsilon", epsilon, "> 0"));
  return CheckOption(z_quantile > 0 && std::isfinite(z_quantile), "KldOptions.z_quantile",
                     z_quantile, "> 0");
}

namespace {

// floor(v / bin) as an integer key; clamped so that absurd (but finite) poses stay defined.
int64_t BinKey(double v, double bin) {
  return static_cast<int64_t>(std::clamp(std::floor(v / bin), -1e15, 1e15));
}

}  // namespace

int CountOccupiedBins(const ParticleSet& particles, const KldOptions& options) {
  std::vector<std::array<int64_t, 3>> keys;
  keys.reserve(particles.size());
  for (const Particle& p : particles) {
    keys.push_back({BinKey(p.pose.x_m, options.bin_xy_m), BinKey(p.pose.y_m, options.bin_xy_m),
                    BinKey(p.pose.theta_rad, options.bin_theta_rad)});
  }
  std::sort(keys.begin(), keys.end());
  return static_cast<int>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

int KldParticleCount(int occupied_bins, const KldOptions& o) {
  if (occupied_bins <= 1) return o.min_particles;
  const double k1 = occupied_bins - 1.0;
  const double a = 2.0 / (9.0 * k1);
  const double b = 1.0 - a + std::sqrt(a) * o.z_quantile;
  const double n = std::ceil(k1 / (2.0 * o.epsilon) * b * b * b);
  return static_cast<int>(std::clamp(n, double(o.min_particles), double(o.max_particles)));
}

}  // namespace fleetmap::vehicle_agent
