#include "vehicle_agent/localization/odometry_path.h"

#include <cmath>

namespace fleetmap::vehicle_agent {

void OdometryPath::Restart(const core::Pose2& from) {
  last_ = from;
  waypoints_.clear();
}

void OdometryPath::Add(const core::Pose2& odometry) {
  if (waypoints_.size() >= max_waypoints_) return;
  const core::Pose2 moved = core::Between(last_, odometry);
  if (std::hypot(moved.x_m, moved.y_m) < step_m_ && std::abs(moved.theta_rad) < step_rad_) return;
  waypoints_.push_back(odometry);
  last_ = odometry;
}

}  // namespace fleetmap::vehicle_agent
