#include "vehicle_agent/mapping/local_mapper.h"

#include <cmath>

#include "core/map/scan_inserter.h"

namespace fleetmap::vehicle_agent {

core::Status LocalMapperOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(map.Validate());
  FLEETMAP_RETURN_IF_ERROR(matcher.Validate());
  if (!(update_min_distance_m >= 0 && update_min_angle_rad >= 0 && min_range_m >= 0 &&
        max_range_m > min_range_m && rest_max_translation_m >= 0 && rest_max_rotation_rad >= 0)) {
    return core::InvalidArgument(
        "local mapper: update and rest thresholds >= 0 and min_range_m < max_range_m");
  }
  return core::OkStatus();
}

namespace {

// Returns beyond max_range_m are neither matched nor inserted.
MultiResolutionMapOptions MapOptions(const LocalMapperOptions& options) {
  MultiResolutionMapOptions map = options.map;
  map.insert.max_range_m = options.max_range_m;
  return map;
}

}  // namespace

LocalMapper::LocalMapper(const LocalMapperOptions& options, const core::Pose2& start_pose)
    : options_(options),
      map_(MapOptions(options), start_pose.translation()),
      pose_(start_pose),
      last_insert_pose_(start_pose) {}

std::vector<Eigen::Vector2d> LocalMapper::EndPoints(const core::LaserScan& scan,
                                                    const core::Pose2& scanner_in_base) {
  if (beams_.directions.size() != scan.size() || beams_.angle_min_rad != scan.angle_min_rad ||
      beams_.angle_increment_rad != scan.angle_increment_rad) {
    beams_.angle_min_rad = scan.angle_min_rad;
    beams_.angle_increment_rad = scan.angle_increment_rad;
    beams_.directions = core::BeamDirections(scan, 0.0);
  }
  std::vector<Eigen::Vector2d> points;
  points.reserve(scan.size());
  for (size_t i = 0; i < scan.size(); ++i) {
    if (!scan.IsValidReturn(i)) continue;
    const double r = scan.ranges_m[i];
    if (r < options_.min_range_m || r > options_.max_range_m) continue;
    points.push_back(scanner_in_base.Apply(r * beams_.directions[i]));
  }
  return points;
}

ScanUpdate LocalMapper::AddScan(const core::LaserScan& scan, const core::Pose2& odometry_delta,
                                const core::Pose2& scanner_in_base) {
  ScanUpdate update;
  const bool at_rest =
      std::hypot(odometry_delta.x_m, odometry_delta.y_m) <= options_.rest_max_translation_m &&
      std::abs(odometry_delta.theta_rad) <= options_.rest_max_rotation_rad &&
      (options_.rest_max_translation_m > 0 || options_.rest_max_rotation_rad > 0);
  if (first_) {
    pose_ = pose_ * odometry_delta;  // nothing to match against yet: odometry places it
  } else {
    const core::Pose2 prediction = pose_ * odometry_delta;
    if (at_rest) {
      pose_ = prediction;
      update.at_rest = true;
    } else {
      update.match = MatchScan(map_, EndPoints(scan, scanner_in_base), prediction, odometry_delta,
                               options_.matcher);
      pose_ = update.match.pose;
      update.matched = true;
    }
  }
  const core::Pose2 moved = core::Between(last_insert_pose_, pose_);
  if (first_ || std::hypot(moved.x_m, moved.y_m) >= options_.update_min_distance_m ||
      std::abs(moved.theta_rad) >= options_.update_min_angle_rad) {
    map_.Insert(scan, pose_ * scanner_in_base);
    last_insert_pose_ = pose_;
    update.inserted = true;
    ++scans_inserted_;
  }
  first_ = false;
  update.pose = pose_;
  return update;
}

}  // namespace fleetmap::vehicle_agent
