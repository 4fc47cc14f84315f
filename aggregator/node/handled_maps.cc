#include "aggregator/node/handled_maps.h"

#include "aggregator/candidates_seen_free.h"

namespace fleetmap::aggregator::node {

void HandledMaps::LoadMerged(const ProvenanceLog& history) {
  for (const MergeCommit& c : history.commits())
    if (c.source.tempmap_sequence != kSeenFreeSequence)  // drops a vehicle reported, no map
      merged_[{c.source.vehicle_id, c.source.tempmap_sequence}] = c.version;
}

void HandledMaps::Merged(const MapKey& key, uint64_t version) { merged_[key] = version; }

void HandledMaps::Rejected(const MapKey& key, uint64_t version) {
  if (rejected_.emplace(key, version).second) rejection_order_.push_back(key);
  while (static_cast<int>(rejection_order_.size()) > max_rejections_) {
    rejected_.erase(rejection_order_.front());
    rejection_order_.pop_front();
  }
}

std::optional<HandledMap> HandledMaps::Find(const MapKey& key) const {
  if (auto it = merged_.find(key); it != merged_.end()) return HandledMap{true, it->second};
  if (auto it = rejected_.find(key); it != rejected_.end()) return HandledMap{false, it->second};
  return std::nullopt;
}

}  // namespace fleetmap::aggregator::node
