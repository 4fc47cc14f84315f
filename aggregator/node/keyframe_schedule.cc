#include "aggregator/node/keyframe_schedule.h"

#include <algorithm>

namespace fleetmap::aggregator::node {

KeyframeSchedule::KeyframeSchedule(int32_t num_tiles, double period_s, double now_s)
    : num_tiles_(std::max(num_tiles, 0)),
      tiles_per_s_(period_s > 0.0 ? num_tiles_ / period_s : 0.0),
      last_s_(now_s),
      asked_(static_cast<size_t>(num_tiles_), false) {}

void KeyframeSchedule::Ask(const std::vector<int32_t>& tiles) {
  const auto ask = [this](int32_t i) {
    if (i < 0 || i >= num_tiles_ || asked_[i]) return;
    asked_[i] = true;
    ++asked_count_;
  };
  if (tiles.empty()) {
    for (int32_t i = 0; i < num_tiles_; ++i) ask(i);
  } else {
    for (int32_t i : tiles) ask(i);
  }
}

double KeyframeSchedule::CreditAt(double now_s) const {
  // At most a second of the pace accumulates (while the link had no room): no burst after.
  const double cap = std::max(1.0, tiles_per_s_);
  return std::min(cap, credit_ + std::max(0.0, now_s - last_s_) * tiles_per_s_);
}

std::optional<int32_t> KeyframeSchedule::NextAsked() {
  if (asked_count_ == 0) return std::nullopt;
  while (!asked_[asked_cursor_]) asked_cursor_ = (asked_cursor_ + 1) % num_tiles_;
  const int32_t tile = asked_cursor_;
  asked_[tile] = false;
  --asked_count_;
  ++asked_sent_;
  asked_cursor_ = (asked_cursor_ + 1) % num_tiles_;
  return tile;
}

std::optional<int32_t> KeyframeSchedule::NextRolling(double now_s) {
  credit_ = CreditAt(now_s);
  last_s_ = std::max(last_s_, now_s);
  if (num_tiles_ == 0 || credit_ < 1.0) return std::nullopt;
  credit_ -= 1.0;
  const int32_t tile = rolling_cursor_;
  rolling_cursor_ = (rolling_cursor_ + 1) % num_tiles_;
  if (rolling_cursor_ == 0) ++rounds_;
  return tile;
}

}  // namespace fleetmap::aggregator::node
