// Where the particles start: around a given pose (a configured or operator-given initial pose,
// an external localization) or spread over the whole free space (global localization).
#pragma once

#include <Eigen/Core>
#include <random>

#include "core/map/occupancy_grid.h"
#include "core/result.h"
#include "vehicle_agent/localization/particle_set.h"

namespace fleetmap::vehicle_agent {

// `count` particles drawn from N(mean, covariance); negative eigenvalues (a covariance that
// is not quite positive semi-definite) are treated as zero. Uniform weights.
ParticleSet SampleAroundPose(const core::Pose2& mean, const Eigen::Matrix3d& covariance, int count,
                             std::mt19937& rng);

// `count` particles uniformly over the free cells of `map` (uniform heading); empty when the
// map has no free cell. Uniform weights.
ParticleSet SampleFreeSpace(const core::OccupancyGrid& map, int count, std::mt19937& rng);

}  // namespace fleetmap::vehicle_agent
