#include "core/pose_covariance.h"

#include <Eigen/Dense>

namespace fleetmap::core {

Eigen::Matrix3d DiagonalCovariance(double sigma_xy_m, double sigma_theta_rad) {
  return Eigen::Vector3d(sigma_xy_m * sigma_xy_m, sigma_xy_m * sigma_xy_m,
                         sigma_theta_rad * sigma_theta_rad)
      .asDiagonal();
}

Eigen::Vector3d PoseDifference(const core::Pose2& a, const core::Pose2& b) {
  return {a.x_m - b.x_m, a.y_m - b.y_m, NormalizeAngle(a.theta_rad - b.theta_rad)};
}

Eigen::Matrix3d InformationMatrix(const Eigen::Matrix3d& cov) {
  return (cov + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
}

double SquaredMahalanobis(const Eigen::Vector3d& d, const Eigen::Matrix3d& cov) {
  return d.dot(InformationMatrix(cov) * d);
}

}  // namespace fleetmap::core
