#include "eval/anchor_consistency.h"

#include "core/pose_covariance.h"

namespace fleetmap::eval {

double AnchorNees(const core::Pose2& anchor, const Eigen::Matrix3d& covariance,
                  const core::Pose2& truth) {
  return core::SquaredMahalanobis(core::PoseDifference(truth, anchor), covariance);
}

}  // namespace fleetmap::eval
