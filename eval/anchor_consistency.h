// Whether a vehicle knows how well it is localized: a temporary map's anchor error against the
// covariance the vehicle sent with it. The aggregator can trust a correction only as far as
// that covariance is honest, so the evaluation measures it (docs/evaluation.md).
#pragma once

#include <Eigen/Core>

#include "core/pose2.h"

namespace fleetmap::eval {

// The normalized estimation error squared of `anchor` against `truth`: e' C^-1 e with e the
// difference (x_m, y_m, theta_rad) in the static frame (the angle wrapped). For an honest
// covariance it follows a chi-square of 3 degrees of freedom: mean 3, 95 % below 7.81. A
// covariance that claims certainty (singular) scores any error as enormous, as it should.
double AnchorNees(const core::Pose2& anchor, const Eigen::Matrix3d& covariance,
                  const core::Pose2& truth);

}  // namespace fleetmap::eval
