#include "vehicle_agent/node/input_queue.h"

namespace fleetmap::vehicle_agent::node {
namespace {

bool IsScan(const SensorInput& input) { return std::holds_alternative<core::LaserScan>(input); }

}  // namespace

void InputQueue::Push(SensorInput input) {
  scans_ += IsScan(input);
  inputs_.push_back(std::move(input));
  while (static_cast<int>(inputs_.size()) > options_.max_queued_inputs) {
    if (IsScan(inputs_.front())) {
      --scans_;
      ++scans_skipped_;
    } else {
      ++inputs_dropped_;
    }
    inputs_.pop_front();
  }
}

std::vector<SensorInput> InputQueue::TakeAll() {
  std::vector<SensorInput> out;
  out.reserve(inputs_.size());
  int scans_to_skip = scans_ > options_.max_queued_scans ? scans_ - 1 : 0;
  scans_skipped_ += scans_to_skip;
  for (SensorInput& input : inputs_) {
    if (scans_to_skip > 0 && IsScan(input)) {
      --scans_to_skip;
      continue;
    }
    out.push_back(std::move(input));
  }
  inputs_.clear();
  scans_ = 0;
  return out;
}

}  // namespace fleetmap::vehicle_agent::node
