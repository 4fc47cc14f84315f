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

Status PoseEstimate::Validate() const {
  if (!std::isfinite(stamp_s) || !pose_in_map.IsFinite() || !covariance.allFinite()) {
    return InvalidArgument("pose estimate has a non-finite field");
  }
  if ((covariance - covariance.transpose()).cwiseAbs().maxCoeff() >
          1e-9 * (1 + covariance.norm()) ||
      covariance(0, 0) < 0 || covariance(1, 1) < 0 || covariance(2, 2) < 0) {
    return InvalidArgument("pose covariance is not symmetric with a non-negative diagonal");
  }
  return OkStatus();
}

}  // namespace fleetmap::core
