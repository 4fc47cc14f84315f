// Wheel odometry and pose estimates as the libraries pass them around, free of any
// middleware type.
#pragma once

#include <Eigen/Core>

#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::core {

// Integrated wheel odometry: the vehicle's pose in its odometry frame, which drifts.
struct OdometrySample {
  double stamp_s = 0.0;
  Pose2 pose_in_odom;
  double v_mps = 0.0;        // forward speed
  double omega_radps = 0.0;  // yaw rate, counter-clockwise positive
  Status Validate() const;
};

// Whether `covariance` (of x_m, y_m, theta_rad) is finite, symmetric, with a non-negative
// diagonal and correlations within [-1, 1]: what a pose's uncertainty from outside must be.
Status ValidatePoseCovariance(const Eigen::Matrix3d& covariance);

// A localized pose in the static map frame with its uncertainty.
struct PoseEstimate {
  double stamp_s = 0.0;
  Pose2 pose_in_map;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // of (x_m, y_m, theta_rad)
  int32_t map_version = 0;
  Status Validate() const;
};

}  // namespace fleetmap::core
