// The vehicle's last good pose, kept in the state folder with the odometry reading it was
// taken at, so that an agent restarted on a vehicle that has not moved (the same odometry)
// starts where it was instead of searching the whole map; a vehicle that moved meanwhile
// (other odometry, or odometry that restarted with the vehicle) searches.
#pragma once

#include <cstdint>
#include <string>

#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::vehicle_agent::node {

struct KeptPose {
  core::Pose2 base_in_map;
  core::Pose2 odometry;  // the odometry sample's pose in the odometry frame at that time
  int32_t map_version = 0;
};

// When the kept pose still holds, and how often it is written.
struct KeptPoseOptions {
  // Written at most this often while the vehicle moves (nothing while it stands), and at
  // exit, s; 0: never kept. Each write is a small file replaced atomically (fsync).
  double period_s = 2.0;
  // The vehicle has not moved when its first odometry sample is this close to the kept one,
  // m and rad, >= 0.
  double same_odometry_m = 0.02;
  double same_odometry_rad = 0.01;
  core::Status Validate() const;
};

class PoseStore {
 public:
  // `state_dir` empty: nothing is kept.
  explicit PoseStore(std::string state_dir) : state_dir_(std::move(state_dir)) {}

  // NotFound when none was kept; DataLoss when the file is not a kept pose.
  core::Result<KeptPose> Load() const;
  core::Status Store(const KeptPose& pose) const;  // atomically

  bool enabled() const { return !state_dir_.empty(); }
  std::string path() const { return state_dir_ + "/last_pose"; }

 private:
  std::string state_dir_;
};

// The kept pose holds: `odometry` (the first sample after the start) is where it was.
bool StillThere(const KeptPose& kept, const core::Pose2& odometry, const KeptPoseOptions& o);

}  // namespace fleetmap::vehicle_agent::node
