#include "vehicle_agent/node/agent_node_options.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace fleetmap::vehicle_agent::node {

core::Status CheckVehicleId(const std::string& id) {
  const bool ok = !id.empty() && id.size() <= 64 && std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (ok) return core::OkStatus();
  return core::InvalidArgument("vehicle_id '" + id +
                               "' must have 1 to 64 characters of A-Z a-z 0-9 _ -");
}

core::Status AgentNodeOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(CheckVehicleId(pipeline.vehicle_id));
  FLEETMAP_RETURN_IF_ERROR(pipeline.Validate());
  FLEETMAP_RETURN_IF_ERROR(outbox.Validate());
  FLEETMAP_RETURN_IF_ERROR(map.Validate());
  FLEETMAP_RETURN_IF_ERROR(last_pose.Validate());
  if (queue.max_queued_scans < 1)
    return core::InvalidArgument("rates.max_queued_scans must be >= 1");
  if (queue.max_queued_inputs < 16)
    return core::InvalidArgument("rates.max_queued_inputs must be >= 16");
  if (initial_pose == InitialPoseSource::kFirstExternal && !use_external_pose)
    return core::InvalidArgument(
        "initial pose from the first external pose needs inputs.external_pose: true");
  if (!(status_period_s > 0.0)) return core::InvalidArgument("rates.status_period_s must be > 0");
  FLEETMAP_RETURN_IF_ERROR(uplink_pacer.Validate().WithContext("rates.uplink_tiles_per_s/burst"));
  if (!std::isfinite(utime_offset_s)) return core::InvalidArgument("utime_offset_s is not finite");
  return core::OkStatus();
}

}  // namespace fleetmap::vehicle_agent::node
