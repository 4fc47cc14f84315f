#include "vehicle_agent/node/tile_send_queue.h"

namespace fleetmap::vehicle_agent::node {

void TileSendQueue::Add(std::vector<core::TempMapTile> tiles) {
  for (core::TempMapTile& tile : tiles) {
    if (queued_.insert({tile.sequence, tile.index}).second) tiles_.push_back(std::move(tile));
  }
}

std::vector<core::TempMapTile> TileSendQueue::Take(double now_s, bool all) {
  const size_t allowed = all ? tiles_.size() : static_cast<size_t>(pacer_.Allowed(now_s));
  std::vector<core::TempMapTile> out;
  while (out.size() < allowed && !tiles_.empty()) {
    queued_.erase({tiles_.front().sequence, tiles_.front().index});
    out.push_back(std::move(tiles_.front()));
    tiles_.pop_front();
  }
  pacer_.Sent(static_cast<int>(out.size()));
  return out;
}

void TileSendQueue::Drop(int32_t sequence, const std::function<bool(int32_t index)>& drop) {
  for (auto it = tiles_.begin(); it != tiles_.end();) {
    if (it->sequence == sequence && drop(it->index)) {
      queued_.erase({it->sequence, it->index});
      it = tiles_.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace fleetmap::vehicle_agent::node
