// Temporary-map tiles on their way out: the outbox says which are due, this queue lets them
// leave at a bounded rate (core::SendPacer), because a map of tens of tiles sent at once
// overflows slow readers (LCM queues 30 messages per subscription and drops the rest). A tile
// that comes due again while its first copy still waits is not queued twice, and tiles an
// acknowledgement made needless leave the queue unsent.
#pragma once

#include <deque>
#include <functional>
#include <set>
#include <utility>
#include <vector>

#include "core/codec/send_pacer.h"
#include "core/codec/temp_map_tiles.h"

namespace fleetmap::vehicle_agent::node {

class TileSendQueue {
 public:
  explicit TileSendQueue(const core::PacerOptions& pacer) : pacer_(pacer) {}

  void Add(std::vector<core::TempMapTile> tiles);
  // The tiles that may leave at `now_s` (all of them when `all`: at exit), oldest first.
  std::vector<core::TempMapTile> Take(double now_s, bool all = false);
  // Forgets the queued tiles of `sequence` whose index `drop` accepts.
  void Drop(int32_t sequence, const std::function<bool(int32_t index)>& drop);

  size_t size() const { return tiles_.size(); }

 private:
  core::SendPacer pacer_;
  std::deque<core::TempMapTile> tiles_;
  std::set<std::pair<int32_t, int32_t>> queued_;  // (sequence, index) of tiles_
};

}  // namespace fleetmap::vehicle_agent::node
