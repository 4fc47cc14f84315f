#include "core/odometry.h"

#include <cmath>

namespace fleetmap::core {

Status OdometrySample::Validate() const {
  if (!std::isfinite(stamp_s) || !pose_in_odom.IsFinite() || !std::isfinite(v_mps) ||
      !std::isfinite(omega_radps)) {
    return InvalidArgument("odometry has a non-finite field");
  }
  return OkStatus();
}

Status ValidatePoseCovariance(const Eigen::Matrix3d& covariance) {
  if (!covariance.allFinite()) return InvalidArgument("pose covariance is not finite");
  if ((covariance - covariance.transpose()).cwiseAbs().maxCoeff() >
          1e-9 * (1 + covariance.norm()) ||
      covariance(0, 0) < 0 || covariance(1, 1) < 0 || covariance(2, 2) < 0) {
    return InvalidArgument("pose covariance is not symmetric with a non-negative diagonal");
  }
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (covariance(i, j) * covariance(i, j) >
          covariance(i, i) * covariance(j, j) * (1 + 1e-9) + 1e-300)
        return InvalidArgument("pose covariance has a correlation beyond [-1, 1]");
  return OkStatus();
}

Status PoseEstimate::Validate() const {
  if (!std::isfinite(stamp_s) || !pose_in_map.IsFinite())
    return InvalidArgument("pose estimate has a non-finite field");
  return ValidatePoseCovariance(covariance);
}

}  // namespace fleetmap::core
