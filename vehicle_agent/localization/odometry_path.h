// The odometry poses passed since the last filter update, kept one every `step` of motion, so
// that the prediction can apply the motion model along the way rather than to the whole
// increment at once. The model's noise grows with the square of an increment: taken at once,
// seconds of motion (an agent that fell behind and skipped scans) spread the particles over
// a metre, and the filter can settle on a wrong mode in a repetitive aisle; taken in steps,
// the spread grows with the square root of the distance, as independent steps do.
#pragma once

#include <cstddef>
#include <vector>

#include "core/pose2.h"

namespace fleetmap::vehicle_agent {

class OdometryPath {
 public:
  // A waypoint is kept when the motion since the last one reaches `step_m` or `step_rad`;
  // after `max_waypoints` the rest of the way is one increment (bounded memory when no filter
  // update runs for long: no map yet, no initial pose).
  OdometryPath(double step_m, double step_rad, size_t max_waypoints = 256)
      : step_m_(step_m), step_rad_(step_rad), max_waypoints_(max_waypoints) {}

  // Forgets the waypoints; the path starts again at `from` (the odometry at a filter update).
  void Restart(const core::Pose2& from);
  // The odometry pose after an accepted increment.
  void Add(const core::Pose2& odometry);

  // Intermediate poses between the Restart pose and the current one, in order.
  const std::vector<core::Pose2>& waypoints() const { return waypoints_; }

 private:
  double step_m_, step_rad_;
  size_t max_waypoints_;
  core::Pose2 last_;  // the last waypoint, or the Restart pose
  std::vector<core::Pose2> waypoints_;
};

}  // namespace fleetmap::vehicle_agent
