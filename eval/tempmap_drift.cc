#include "eval/tempmap_drift.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::eval {

TempMapDrift BuilderDrift(const std::vector<core::TimedPose>& trajectory_in_temp,
                          const std::function<core::Pose2(double)>& truth_at) {
  if (trajectory_in_temp.empty()) return {std::nan(""), std::nan("")};
  const core::TimedPose& first = trajectory_in_temp.front();
  const core::Pose2 truth_first = truth_at(first.stamp_s);
  TempMapDrift drift;
  for (const core::TimedPose& p : trajectory_in_temp) {
    const core::Pose2 moved = core::Between(truth_first, truth_at(p.stamp_s));
    const core::Pose2 built = core::Between(first.pose, p.pose);
    const core::Pose2 error = core::Between(moved, built);
    drift.translation_m = std::max(drift.translation_m, std::hypot(error.x_m, error.y_m));
    drift.rotation_deg = std::max(drift.rotation_deg, std::abs(error.theta_rad) * 180 / M_PI);
  }
  return drift;
}

}  // namespace fleetmap::eval
