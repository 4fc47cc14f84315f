// The temporary maps the aggregator has finished with, so that a resend (the vehicle missed
// the acknowledgement) is answered DUPLICATE and never merged twice. Merged maps come from
// the current map's history (every commit names its vehicle and sequence), which the journal
// restores after a restart, so they are remembered for as long as the map is. Rejected maps
// are remembered in memory, the newest max_rejections of them: a rejection depends only on
// the map and the static map, so one forgotten and sent again is rejected again.
#pragma once

#include <deque>
#include <map>
#include <optional>

#include "aggregator/node/map_key.h"
#include "aggregator/provenance.h"

namespace fleetmap::aggregator::node {

struct HandledMap {
  bool merged = false;
  uint64_t version = 0;  // merged: the version the merge created; rejected: the version then
};

class HandledMaps {
 public:
  explicit HandledMaps(int max_rejections) : max_rejections_(max_rejections) {}

  // Every merge in the current map's history.
  void LoadMerged(const ProvenanceLog& history);
  void Merged(const MapKey& key, uint64_t version);
  void Rejected(const MapKey& key, uint64_t version);
  std::optional<HandledMap> Find(const MapKey& key) const;

  size_t merged() const { return merged_.size(); }
  size_t rejected() const { return rejected_.size(); }

 private:
  int max_rejections_;
  std::map<MapKey, uint64_t> merged_;    // -> version created
  std::map<MapKey, uint64_t> rejected_;  // -> version at the rejection
  std::deque<MapKey> rejection_order_;   // oldest first
};

}  // namespace fleetmap::aggregator::node
