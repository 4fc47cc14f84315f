// A temporary map: the small local grid one vehicle builds while it sees a change, and what
// the aggregator merges. Frames: the map's own frame T is the vehicle base at the moment the
// map was started; `grid`'s geometry origin is expressed in T; `anchor_in_map` is where the
// vehicle's localization put T in the static map frame. Placing the map by its anchor is
// therefore GridGeometry with origin anchor_in_map * grid.geometry().origin().
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/map/occupancy_grid.h"

namespace fleetmap::core {

struct TimedPose {
  double stamp_s = 0.0;
  Pose2 pose;
};

struct TempMap {
  std::string vehicle_id;
  int32_t sequence = 0;  // per vehicle, +1 per temporary map
  Pose2 anchor_in_map;   // localized vehicle pose where the map started
  // How sure the localizer was of the anchor: its covariance of (x_m, y_m, theta_rad) in the
  // static map frame. None where the map's source has no localizer (a map made from the
  // truth, a file from before it was kept).
  std::optional<Eigen::Matrix3d> anchor_covariance;
  OccupancyGrid grid;  // log-odds evidence, geometry origin in the map's frame T
  std::vector<TimedPose> trajectory_in_temp;  // vehicle poses in T while building
  double start_s = 0.0;
  double end_s = 0.0;

  // The grid's geometry placed in the static map frame by the anchor (and an optional
  // correction applied in the static frame on top: correction * anchor).
  GridGeometry PlacedGeometry(const Pose2& correction = {}) const;
  // Sizes, finite anchor (and a valid covariance where there is one), times in order, vehicle
  // id present.
  Status Validate() const;
};

}  // namespace fleetmap::core
