#include "eval/anchor_consistency.h"

#include "vehicle_agent/localization/pose_covariance.h"

namespace fleetmap::eval {

double AnchorNees(const core::Pose2& anchor, const Eigen::Matrix3d& covariance,
                  const core::Pose2& truth) {
  return vehicle_agent::SquaredMahalanobis(vehicle_agent::PoseDifference(truth, anchor),
                                           covariance);
}

}  // namespace fleetmap::eval
