#include "aggregator/node/request_queue.h"

#include <algorithm>

namespace fleetmap::aggregator::node {

void RequestQueue::AddDeltas(uint64_t from_version) {
  deltas_from_ = deltas_from_ ? std::min(*deltas_from_, from_version) : from_version;
}

void RequestQueue::AddKeyframe(const std::vector<int32_t>& tiles) {
  if (tiles.empty()) {
    full_ = true;
    tiles_.clear();
    return;
  }
  if (!full_) tiles_.insert(tiles.begin(), tiles.end());
}

RequestPlan RequestQueue::Take(double now_s) {
  RequestPlan plan;
  plan.deltas_from = deltas_from_;
  deltas_from_.reset();
  if (keyframe_waiting() && now_s - last_keyframe_s_ >= keyframe_min_interval_s_) {
    plan.full_keyframe = full_;
    plan.keyframe_tiles.assign(tiles_.begin(), tiles_.end());
    full_ = false;
    tiles_.clear();
    last_keyframe_s_ = now_s;
  }
  return plan;
}

void RequestQueue::WholeKeyframeSent(double now_s) {
  last_keyframe_s_ = now_s;
  full_ = false;
  tiles_.clear();
}

}  // namespace fleetmap::aggregator::node
