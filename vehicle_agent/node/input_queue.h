// The sensor inputs waiting for the next processing pass, in arrival order. Handlers only
// queue (no work inside an LCM callback); the node processes the queue once per loop. When
// the agent falls behind, the queue keeps only the newest scan and says how many it skipped:
// a late pose is worth less than a current one, and nothing is dropped without a count.
// Odometry and external poses are kept in order (they are cheap, and the localizer needs
// every odometry increment).
#pragma once

#include <cstdint>
#include <deque>
#include <variant>
#include <vector>

#include "core/odometry.h"
#include "core/scan.h"

namespace fleetmap::vehicle_agent::node {

struct ExternalPoseInput {
  core::PoseEstimate pose;
};

using SensorInput = std::variant<core::LaserScan, core::OdometrySample, ExternalPoseInput>;

struct InputQueueOptions {
  int max_queued_scans = 3;      // more scans waiting than this: keep only the newest, >= 1
  int max_queued_inputs = 4096;  // hard bound on everything queued (oldest dropped), >= 16
};

class InputQueue {
 public:
  explicit InputQueue(const InputQueueOptions& options) : options_(options) {}

  void Push(SensorInput input);
  // Everything queued, in order, after skipping scans when there are too many.
  std::vector<SensorInput> TakeAll();

  size_t size() const { return inputs_.size(); }
  int64_t scans_skipped() const { return scans_skipped_; }
  int64_t inputs_dropped() const { return inputs_dropped_; }  // by the hard bound

 private:
  InputQueueOptions options_;
  std::deque<SensorInput> inputs_;
  int scans_ = 0;
  int64_t scans_skipped_ = 0;
  int64_t inputs_dropped_ = 0;
};

}  // namespace fleetmap::vehicle_agent::node
