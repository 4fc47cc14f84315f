#include "core/map/temp_map.h"

#include <cmath>

#include "core/odometry.h"

namespace fleetmap::core {

GridGeometry TempMap::PlacedGeometry(const Pose2& correction) const {
  const GridGeometry& g = grid.geometry();
  return GridGeometry(g.resolution_m(), g.width(), g.height(),
                      correction * anchor_in_map * g.origin());
}

Status TempMap::Validate() const {
  if (vehicle_id.empty()) return InvalidArgument("temporary map without a vehicle id");
  FLEETMAP_RETURN_IF_ERROR(grid.geometry().Validate().WithContext("temporary map grid"));
  if (!anchor_in_map.IsFinite()) return InvalidArgument("temporary map anchor pose is not finite");
  if (anchor_covariance)
    FLEETMAP_RETURN_IF_ERROR(
        ValidatePoseCovariance(*anchor_covariance).WithContext("temporary map anchor"));
  if (!std::isfinite(start_s) || !std::isfinite(end_s) || end_s < start_s) {
    return InvalidArgument("temporary map times are not finite or end before they start");
  }
  return OkStatus();
}

}  // namespace fleetmap::core
