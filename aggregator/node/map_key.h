// Which temporary map: a vehicle's id and its sequence number for the map.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>

namespace fleetmap::aggregator::node {

// Vehicle ids come from the network: a log line quotes at most this much of one, and a
// MAP_REQUEST naming a longer one is refused. The journal's bound (merge_commit.h) is wider.
constexpr size_t kMaxUplinkVehicleIdBytes = 64;

struct MapKey {
  std::string vehicle_id;
  int32_t sequence = 0;
  bool operator<(const MapKey& o) const {
    return std::tie(vehicle_id, sequence) < std::tie(o.vehicle_id, o.sequence);
  }
  bool operator==(const MapKey& o) const {
    return vehicle_id == o.vehicle_id && sequence == o.sequence;
  }
  std::string ToString() const { return vehicle_id + "#" + std::to_string(sequence); }
};

}  // namespace fleetmap::aggregator::node
