// Which temporary map: a vehicle's id and its sequence number for the map.
#pragma once

#include <cstdint>
#include <string>
#include <tuple>

namespace fleetmap::aggregator::node {

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
