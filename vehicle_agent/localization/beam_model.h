// The beam range-finder model (Thrun, Burgard, Fox: Probabilistic Robotics, ch. 6.3, table
// 6.1): each beam's range z is explained by a mixture of a hit on the expected surface z*
// (ray cast in the map), an unexpected short obstacle, a max-range failure and random noise:
//   p(z | x, m) = z_hit p_hit + z_short p_short + z_max p_max + z_rand p_rand
// with p_hit = eta N(z; z*, sigma_hit^2) on [0, z_max], p_short = eta lambda e^(-lambda z) on
// [0, z*], p_max = 1 at z = z_max and p_rand = 1 / z_max on [0, z_max). It sees both a new
// obstacle (short readings) and a removed one (long readings through a mapped obstacle), which
// the likelihood field cannot: this is the paper's eq. (1) model.
#pragma once

#include <memory>

#include "core/result.h"
#include "vehicle_agent/localization/scan_likelihood.h"

namespace fleetmap::vehicle_agent {

// Defaults are ROS 1 AMCL's laser_* defaults (amcl_node.cpp; they follow Probabilistic
// Robotics' table 6.1 and need not sum to 1), except beam_stride and max_range_m.
struct BeamModelOptions {
  double z_hit = 0.95;   // weight of the hit component, >= 0 (AMCL laser_z_hit)
  double z_short = 0.1;  // weight of unexpected short obstacles, >= 0 (AMCL laser_z_short)
  double z_max = 0.05;   // weight of max-range failures, >= 0 (AMCL laser_z_max)
  double z_rand = 0.05;  // weight of uniform noise, >= 0 (AMCL laser_z_rand)
  // Standard deviation of the hit component, m, > 0 (AMCL laser_sigma_hit). Wider than the
  // S300's 2 cm noise: it also absorbs map discretisation (5 cm) and pose error.
  double sigma_hit_m = 0.2;
  double lambda_short_per_m = 0.1;  // decay of the short component, 1/m, > 0 (AMCL)
  // Use every beam_stride-th beam, >= 1. On the S300 (541 beams) 2 halves the ray casting
  // while W_avg stays close to all beams' and hardly noisier from scan to scan (figures:
  // docs/localization.md, "Scan likelihood").
  int beam_stride = 2;
  // The model's z_max, m, > 0: readings at or beyond min(this, the scan's range_max_m) are
  // "no return". 30 m is the S300's range.
  double max_range_m = 30.0;

  core::Status Validate() const;
};

// A ScanLikelihood using the beam model; expected ranges come from core::RayCaster on the
// map's occupied cells (exact first solid cell, distance-field accelerated).
std::unique_ptr<ScanLikelihood> MakeBeamModel(const BeamModelOptions& options);

// The probability of one reading, exposed for tests: `z_m` the measured range (>= the model's
// max range: no return), `expected_m` the ray-cast range (>= max range: nothing in reach).
double BeamProbability(const BeamModelOptions& options, double z_m, double expected_m,
                       double max_range_m);

}  // namespace fleetmap::vehicle_agent
