// Complete temporary maps over their vehicle's merge rate (vehicle_limits.h), held in each
// vehicle's order until the rate lets them through: a log replayed faster than its stamps
// allow, or a vehicle's backlog after an outage, is merged later rather than dropped. Bounded;
// a map that finds no room waits, unacknowledged, for the vehicle's resend. The tiles of a
// held map stay in the spool, so a restart does not lose it either.
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "aggregator/node/map_key.h"
#include "core/map/temp_map.h"

namespace fleetmap::aggregator::node {

struct HeldMap {
  MapKey key;
  core::TempMap map;
  int32_t tile_count = 0;
  double map_s = 0.0;  // the map's stamp
};

class HeldMaps {
 public:
  explicit HeldMaps(int capacity) : capacity_(capacity) {}

  // False when full.
  bool Hold(HeldMap map);
  // The vehicle has maps waiting: its next one must wait behind them.
  bool Waiting(const std::string& vehicle) const { return queues_.count(vehicle) > 0; }
  bool Contains(const MapKey& key) const;
  // The maps whose turn has come, each vehicle's in its order: `allow(vehicle, map_s)` is
  // asked for each vehicle's oldest held map until it says no.
  std::vector<HeldMap> Release(const std::function<bool(const std::string&, double)>& allow);
  int size() const { return size_; }

 private:
  int capacity_;
  int size_ = 0;
  std::map<std::string, std::deque<HeldMap>> queues_;
};

}  // namespace fleetmap::aggregator::node
