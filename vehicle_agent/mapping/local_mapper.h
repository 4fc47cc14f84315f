// Incremental scan-matching mapping around a start pose: each scan is matched against the
// map built so far (odometry as the prior), and inserted into it once the vehicle has moved
// enough since the last insertion (repeated insertions from one spot only sharpen noise).
// The temporary-map builder runs one; fleetmap-carmen-eval runs one over whole logs.
#pragma once

#include "core/scan.h"
#include "vehicle_agent/mapping/scan_matcher.h"

namespace fleetmap::vehicle_agent {

struct LocalMapperOptions {
  MultiResolutionMapOptions map;
  ScanMatcherOptions matcher;
  double update_min_distance_m = 0.1;  // insert a scan after this much travel ...
  double update_min_angle_rad = 0.1;   // ... or this much turning
  double min_range_m = 0.1;            // end points closer than this are not matched
  double max_range_m = 25.0;           // ... nor farther than this
  // Odometry steps at most this small mean the vehicle stands still: its scan is not matched
  // (the pose follows the odometry). Matching again what was just matched from the same spot
  // only re-fits sensor noise, and a parked vehicle should cost nothing; MRPT's icp-slam
  // likewise matches only after 0.2 m or 5 deg. 0 and 0: match every scan.
  double rest_max_translation_m = 1e-4;
  double rest_max_rotation_rad = 1e-4;
  core::Status Validate() const;
};

struct ScanUpdate {
  core::Pose2 pose;  // base pose in the mapper's frame after matching
  MatchResult match;
  bool inserted = false;  // the scan went into the map
  bool matched = false;   // false for the first scan (nothing to match against yet) ...
  bool at_rest = false;   // ... and for a vehicle standing still
};

class LocalMapper {
 public:
  // The map's frame is the one `start_pose` is given in; the map is centred on it.
  explicit LocalMapper(const LocalMapperOptions& options, const core::Pose2& start_pose = {});

  // `odometry_delta` is the base's motion since the previous scan (in the previous base frame);
  // for the first scan, since `start_pose`.
  ScanUpdate AddScan(const core::LaserScan& scan, const core::Pose2& odometry_delta,
                     const core::Pose2& scanner_in_base);

  const core::Pose2& pose() const { return pose_; }
  const MultiResolutionMap& map() const { return map_; }
  int scans_inserted() const { return scans_inserted_; }

 private:
  std::vector<Eigen::Vector2d> EndPoints(const core::LaserScan& scan,
                                         const core::Pose2& scanner_in_base);

  // The beams' unit vectors in the scanner frame, kept while the scanner's geometry stays.
  struct BeamTable {
    double angle_min_rad = 0, angle_increment_rad = 0;
    std::vector<Eigen::Vector2d> directions;
  } beams_;
  LocalMapperOptions options_;
  MultiResolutionMap map_;
  core::Pose2 pose_;
  core::Pose2 last_insert_pose_;
  bool first_ = true;
  int scans_inserted_ = 0;
};

}  // namespace fleetmap::vehicle_agent
