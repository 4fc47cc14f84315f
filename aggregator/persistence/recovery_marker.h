// What `fleetmap-mapctl recover` leaves in a state folder for the aggregator: which recovery
// it was, the map version it kept and when. The aggregator names the recovery in its STATUS
// for a while (node.recovery_request_s), and every vehicle sends again the merged maps it
// holds from later versions (vehicle_agent/retained_maps.h): the acknowledged merges the
// damaged files lost come back from the fleet. A text file of three `key value` lines.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/result.h"

namespace fleetmap::aggregator {

constexpr const char* kRecoveryMarkerName = "recovery";

struct RecoveryMarker {
  int64_t id = 0;        // unique per recovery: microseconds since the Unix epoch at the time
  uint64_t version = 0;  // the version the recovery kept
  double at_s = 0.0;     // when, Unix seconds
};

core::Status WriteRecoveryMarker(const std::string& folder, const RecoveryMarker& marker);
// None when the folder has no marker; DataLoss naming the file when it cannot be read as one.
core::Result<std::optional<RecoveryMarker>> ReadRecoveryMarker(const std::string& folder);

}  // namespace fleetmap::aggregator
