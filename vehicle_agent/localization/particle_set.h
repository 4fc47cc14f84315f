// A weighted set of pose hypotheses (particles) and what the filter computes from it: the
// normalised weights, the effective sample size and the mean pose with its covariance.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"

namespace fleetmap::vehicle_agent {

struct Particle {
  core::Pose2 pose;     // vehicle base in the map frame
  double weight = 1.0;  // normalised over the set after every update
  // The vehicle's distance per odometry distance as this particle holds it
  // (odometry_scale.h).
  double odometry_scale = 1.0;
};

using ParticleSet = std::vector<Particle>;

// Scales the weights to sum to 1. When their sum is not positive and finite (every particle
// impossible, or NaN) the weights become uniform and false is returned.
bool NormalizeWeights(ParticleSet& particles);

// 1 / sum(w^2) of normalised weights: N for uniform weights, 1 when one particle has them all.
double EffectiveSampleSize(const ParticleSet& particles);

struct PoseMoments {
  core::Pose2 mean;  // weighted mean; the heading is the circular mean
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // of (x_m, y_m, theta_rad)
};

// Weighted mean and covariance (headings as differences to the circular mean). Needs a
// non-empty set with normalised weights.
PoseMoments ComputeMoments(const ParticleSet& particles);

}  // namespace fleetmap::vehicle_agent
