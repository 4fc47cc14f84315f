// The vehicle's odometry scale as part of each particle's state. Wheels whose diameter is a
// few percent off make the odometry's distances a few percent off, the same way for the whole
// drive: an error the motion model's per-step noise cannot describe (it grows with the
// distance, the noise with its square root). Along an aisle or across an open hall, where the
// laser fixes little along the travel, particles that all share the odometry's scale agree on
// a pose that is off. Each particle therefore carries its own scale, drawn around the set's
// estimate when particles are drawn afresh and wandering a little as the vehicle drives; the
// particles whose scale is right are the ones that still fit where the laser fixes the
// position again (the end of an aisle), and resampling keeps them.
#pragma once

#include <random>

#include "core/pose2.h"
#include "core/result.h"
#include "vehicle_agent/localization/particle_set.h"

namespace fleetmap::vehicle_agent {

struct OdometryScaleOptions {
  // Spread of the scale where particles are drawn afresh, standard deviation of the ratio,
  // >= 0 (0: all start at the set's estimate and the walk below finds the scale). An AGV's
  // uncalibrated wheels are off by a few percent, but a spread drawn together with an
  // uncertain initial pose lets the filter explain the pose's error by a scale: 0.05 kept a
  // vehicle started 0.5 m off 0.15-0.25 m off for 40 s (docs/localization.md).
  double initial_sigma = 0.0;
  // How far a particle's scale wanders per metre driven, standard deviation per sqrt(m),
  // >= 0: keeps a variety of scales in the set after resampling narrowed it.
  double walk_sigma_per_sqrt_m = 0.005;
  // Distance over which a particle's scale is drawn back to 1, m, >= 0 (0: never).
  // Where the laser cannot tell the scale (an open hall, a turn on the spot) the walk alone
  // lets the set's scale drift away from the truth, and a drift of a few percent moves the
  // vehicle's pose as much as the scale error it was meant to correct. The pull makes the
  // scale a mean-reverting walk around the nominal wheels: its stationary spread is
  // walk_sigma_per_sqrt_m * sqrt(pull_distance_m / 2), 0.027 at the defaults. Chosen on the
  // world suite: 20 m pulled too hard to learn a scale, without pull the LivingLab fleet's
  // scales wandered (docs/localization.md).
  double pull_distance_m = 60.0;
  // A particle's scale stays within 1 +- this, (0, 0.5].
  double max_deviation = 0.15;
  core::Status Validate() const;
};

// Draws every particle's scale around `center` (the set's estimate so far).
void DrawOdometryScales(ParticleSet& particles, double center, const OdometryScaleOptions& options,
                        std::mt19937& rng);

// `delta_in_base` with its translation times `scale`.
core::Pose2 ScaledIncrement(const core::Pose2& delta_in_base, double scale);

// A particle's scale after the vehicle drove `translation_m`.
double WalkOdometryScale(double scale, double translation_m, const OdometryScaleOptions& options,
                         std::mt19937& rng);

// The weighted mean scale of a set (normalised weights).
double MeanOdometryScale(const ParticleSet& particles);

}  // namespace fleetmap::vehicle_agent
