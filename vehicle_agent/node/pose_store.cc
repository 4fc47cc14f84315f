#include "vehicle_agent/node/pose_store.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/io/file_io.h"

namespace fleetmap::vehicle_agent::node {

// One line: the format's name, the pose, the odometry and the map version.
constexpr char kFormat[] = "fleetmap-last-pose-1";

core::Status KeptPoseOptions::Validate() const {
  if (!(period_s >= 0 && std::isfinite(period_s) && same_odometry_m >= 0 && same_odometry_rad >= 0))
    return core::InvalidArgument(
        "last_pose: period_s, same_odometry_m and same_odometry_rad must be >= 0");
  return core::OkStatus();
}

core::Result<KeptPose> PoseStore::Load() const {
  if (state_dir_.empty()) return core::NotFound("no state folder");
  core::Result<std::string> text = core::ReadFileBytes(path(), 512);
  if (!text.ok()) return text.status();
  std::istringstream in(*text);
  std::string format;
  KeptPose k;
  in >> format >> k.base_in_map.x_m >> k.base_in_map.y_m >> k.base_in_map.theta_rad >>
      k.odometry.x_m >> k.odometry.y_m >> k.odometry.theta_rad >> k.map_version;
  std::string rest;
  if (format != kFormat || in.fail() || (in >> rest) || !k.base_in_map.IsFinite() ||
      !k.odometry.IsFinite())
    return core::DataLoss(path() + ": not a kept pose (" + kFormat +
                          " x y theta odometry version)");
  return k;
}

core::Status PoseStore::Store(const KeptPose& k) const {
  if (state_dir_.empty()) return core::OkStatus();
  char line[256];
  const int n = std::snprintf(line, sizeof(line), "%s %.6f %.6f %.6f %.6f %.6f %.6f %d\n", kFormat,
                              k.base_in_map.x_m, k.base_in_map.y_m, k.base_in_map.theta_rad,
                              k.odometry.x_m, k.odometry.y_m, k.odometry.theta_rad, k.map_version);
  std::error_code ec;
  std::filesystem::create_directories(state_dir_, ec);
  return core::WriteFileAtomically(path(), std::string(line, static_cast<size_t>(n)));
}

bool StillThere(const KeptPose& kept, const core::Pose2& odometry, const KeptPoseOptions& o) {
  const core::Pose2 moved = core::Between(kept.odometry, odometry);
  return std::hypot(moved.x_m, moved.y_m) <= o.same_odometry_m &&
         std::abs(moved.theta_rad) <= o.same_odometry_rad;
}

}  // namespace fleetmap::vehicle_agent::node
