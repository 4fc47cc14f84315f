#include "aggregator/node/held_maps.h"

#include <algorithm>

namespace fleetmap::aggregator::node {

bool HeldMaps::Hold(HeldMap map) {
  if (size_ >= capacity_) return false;
  queues_[map.key.vehicle_id].push_back(std::move(map));
  ++size_;
  return true;
}

bool HeldMaps::Contains(const MapKey& key) const {
  auto it = queues_.find(key.vehicle_id);
  if (it == queues_.end()) return false;
  return std::any_of(it->second.begin(), it->second.end(),
                     [&](const HeldMap& m) { return m.key.sequence == key.sequence; });
}

std::vector<HeldMap> HeldMaps::Release(
    const std::function<bool(const std::string&, double)>& allow) {
  std::vector<HeldMap> due;
  for (auto it = queues_.begin(); it != queues_.end();) {
    std::deque<HeldMap>& queue = it->second;
    while (!queue.empty() && allow(it->first, queue.front().map_s)) {
      due.push_back(std::move(queue.front()));
      queue.pop_front();
      --size_;
    }
    it = queue.empty() ? queues_.erase(it) : std::next(it);
  }
  return due;
}

}  // namespace fleetmap::aggregator::node
