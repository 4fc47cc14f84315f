// Pose uncertainty as the localizer, the aggregator and the evaluation handle it: Gaussians over
// (x_m, y_m, theta_rad), the heading difference wrapped so that headings either side of +-pi are
// close.
#pragma once

#include <Eigen/Core>

#include "core/pose2.h"

namespace fleetmap::core {

// The covariance of independent errors with these standard deviations.
Eigen::Matrix3d DiagonalCovariance(double sigma_xy_m, double sigma_theta_rad);

// a - b as (dx_m, dy_m, dtheta_rad), dtheta wrapped into (-pi, pi].
Eigen::Vector3d PoseDifference(const core::Pose2& a, const core::Pose2& b);

// cov^-1, with a tiny regularisation so that a singular covariance stays usable.
Eigen::Matrix3d InformationMatrix(const Eigen::Matrix3d& cov);

// d' cov^-1 d (with InformationMatrix's regularisation).
double SquaredMahalanobis(const Eigen::Vector3d& d, const Eigen::Matrix3d& cov);

}  // namespace fleetmap::core
