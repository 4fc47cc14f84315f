#include "vehicle_agent/localization/odometry_scale.h"

#include <algorithm>
#include <cmath>

#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {
namespace {

double Clamp(double scale, const OdometryScaleOptions& o) {
  return std::clamp(scale, 1.0 - o.max_deviation, 1.0 + o.max_deviation);
}

}  // namespace

core::Status OdometryScaleOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(CheckOption(initial_sigma >= 0 && std::isfinite(initial_sigma),
                                       "OdometryScaleOptions.initial_sigma", initial_sigma,
                                       ">= 0 and finite"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(
      walk_sigma_per_sqrt_m >= 0 && std::isfinite(walk_sigma_per_sqrt_m),
      "OdometryScaleOptions.walk_sigma_per_sqrt_m", walk_sigma_per_sqrt_m, ">= 0 and finite"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(pull_distance_m >= 0 && std::isfinite(pull_distance_m),
                                       "OdometryScaleOptions.pull_distance_m", pull_distance_m,
                                       ">= 0 and finite (0: no pull)"));
  return CheckOption(max_deviation > 0 && max_deviation <= 0.5,
                     "OdometryScaleOptions.max_deviation", max_deviation, "in (0, 0.5]");
}

void DrawOdometryScales(ParticleSet& particles, double center, const OdometryScaleOptions& options,
                        std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  for (Particle& p : particles)
    p.odometry_scale = Clamp(center + options.initial_sigma * normal(rng), options);
}

core::Pose2 ScaledIncrement(const core::Pose2& delta_in_base, double scale) {
  return {delta_in_base.x_m * scale, delta_in_base.y_m * scale, delta_in_base.theta_rad};
}

double WalkOdometryScale(double scale, double translation_m, const OdometryScaleOptions& options,
                         std::mt19937& rng) {
  if (translation_m <= 0) return scale;
  if (options.pull_distance_m > 0)
    scale += (1.0 - scale) * std::min(1.0, translation_m / options.pull_distance_m);
  if (options.walk_sigma_per_sqrt_m <= 0) return scale;
  std::normal_distribution<double> normal(0.0, 1.0);
  return Clamp(scale + options.walk_sigma_per_sqrt_m * std::sqrt(translation_m) * normal(rng),
               options);
}

double MeanOdometryScale(const ParticleSet& particles) {
  double sum = 0.0, weights = 0.0;
  for (const Particle& p : particles) sum += p.weight * p.odometry_scale, weights += p.weight;
  return weights > 0 ? sum / weights : 1.0;
}

}  // namespace fleetmap::vehicle_agent
