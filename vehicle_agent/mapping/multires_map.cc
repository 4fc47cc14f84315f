#include "vehicle_agent/mapping/multires_map.h"

#include <cmath>

namespace fleetmap::vehicle_agent {

core::Status MultiResolutionMapOptions::Validate() const {
  if (!(resolution_m > 0 && levels >= 1 && levels <= 5 && size_m > resolution_m * (1 << levels))) {
    return core::InvalidArgument(
        "multi-resolution map: resolution_m > 0, levels in 1..5 and "
        "size_m larger than the coarsest cell are required");
  }
  if (std::pow(size_m / resolution_m, 2) > 64e6) {
    return core::OutOfRange("multi-resolution map: size_m / resolution_m is too large");
  }
  FLEETMAP_RETURN_IF_ERROR(moving.Validate());
  return insert.Validate();
}

MultiResolutionMap::MultiResolutionMap(const MultiResolutionMapOptions& options,
                                       const Eigen::Vector2d& center_m)
    : options_(options) {
  const core::Pose2 origin(center_m.x() - options.size_m / 2, center_m.y() - options.size_m / 2, 0);
  for (int i = 0; i < options.levels; ++i) {
    const double res = options.resolution_m * (1 << i);
    const int cells = static_cast<int>(std::ceil(options.size_m / res));
    levels_.emplace_back(core::GridGeometry(res, cells, cells, origin));
  }
  moving_ = core::MovingCells(levels_.front().geometry(), options.moving);
}

void MultiResolutionMap::Insert(const core::LaserScan& scan, const core::Pose2& scanner_in_map) {
  // One scan, one pose: every level's beams point the same way.
  const std::vector<Eigen::Vector2d> directions =
      core::BeamDirections(scan, scanner_in_map.theta_rad);
  for (size_t i = 0; i < levels_.size(); ++i) {
    core::InsertScan(scan, scanner_in_map, options_.insert, directions, levels_[i],
                     i == 0 ? &moving_ : nullptr);
  }
}

bool MultiResolutionMap::Inside(const Eigen::Vector2d& p, double margin_m) const {
  const core::Pose2& o = finest().geometry().origin();
  return p.x() - o.x_m >= margin_m && p.y() - o.y_m >= margin_m &&
         o.x_m + options_.size_m - p.x() >= margin_m && o.y_m + options_.size_m - p.y() >= margin_m;
}

}  // namespace fleetmap::vehicle_agent
