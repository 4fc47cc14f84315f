// Resampling a particle set: the low-variance (systematic) sampler of Probabilistic
// Robotics, table 4.4, and the KLD-sampling bound on how many particles the posterior needs
// (Fox, "Adapting the sample size in particle filters through KLD-sampling", IJRR 2003).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "core/result.h"
#include "vehicle_agent/localization/particle_set.h"

namespace fleetmap::vehicle_agent {

// Draws `count` particles from `particles` (normalised weights) with one random number: a
// comb of `count` equally spaced teeth over the cumulative weights. Particles with weight
// w are copied count * w times, give or take one. The result has uniform weights.
ParticleSet LowVarianceResample(const ParticleSet& particles, size_t count, std::mt19937& rng);

// Defaults: bins as AMCL's pf_kdtree (0.5 m, 0.5 m, 10 deg), epsilon as nav2's pf_err.
struct KldOptions {
  // Never fewer particles, >= 1. AMCL: 100 (ROS 1), 500 (nav2). On the simulator 100, 200 and
  // 500 track alike (docs/localization.md); 200 keeps a margin for real maps at a sixth of a
  // millisecond per scan.
  int min_particles = 200;
  // Never more, >= min_particles. Initialisation (around a pose or global) starts with this
  // many; AMCL: 5000 (ROS 1), 2000 (nav2).
  int max_particles = 3000;
  double bin_xy_m = 0.5;                   // histogram bin edge in x and y, m, > 0
  double bin_theta_rad = 10 * M_PI / 180;  // histogram bin edge in heading, rad, > 0
  // Bound on the KL divergence between the sample and the true posterior, > 0.
  double epsilon = 0.05;
  // Upper standard normal quantile z_(1-delta), > 0: 2.326 for delta = 0.01. (AMCL passes its
  // kld_z = 0.99 straight into this place of the formula, i.e. a far looser bound.)
  double z_quantile = 2.326;

  core::Status Validate() const;
};

// Number of histogram bins of `options` that hold at least one particle.
int CountOccupiedBins(const ParticleSet& particles, const KldOptions& options);

// Fox's bound for k occupied bins, clamped to [min_particles, max_particles]:
//   n = (k - 1) / (2 epsilon) * (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1))) z)^3.
int KldParticleCount(int occupied_bins, const KldOptions& options);

}  // namespace fleetmap::vehicle_agent
