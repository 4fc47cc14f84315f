// The vehicle's own sensors on their way to the pipeline: SCAN_<id>, ODOM_<id> and EXTPOSE_<id>
// from the sensor link, and scans and odometry from drivers at the process edge, decoded,
// checked (MessageChecks) and queued for the node's next processing pass. Nothing is
// processed here: the link handlers run inside LCM callbacks.
#pragma once

#include <string>
#include <vector>

#include "core/odometry.h"
#include "core/scan.h"
#include "vehicle_agent/node/input_queue.h"
#include "vehicle_agent/node/message_checks.h"

namespace fleetmap::vehicle_agent::node {

class SensorIntake {
 public:
  // `checks` outlives the intake.
  SensorIntake(std::string vehicle_id, const InputQueueOptions& queue, MessageChecks* checks);

  // The payload of a message on the vehicle's sensor channels.
  void OnScan(const void* data, int size);
  void OnOdometry(const void* data, int size);
  void OnExternalPose(const void* data, int size);
  // Input from drivers: already decoded, still checked.
  void OnDriverScan(const core::LaserScan& scan);
  void OnDriverOdometry(const core::OdometrySample& odom);

  // Everything queued since the last call, in order (InputQueue::TakeAll).
  std::vector<SensorInput> TakeAll() { return queue_.TakeAll(); }
  const InputQueue& queue() const { return queue_; }

 private:
  const std::string vehicle_id_;
  MessageChecks* const checks_;
  InputQueue queue_;
};

}  // namespace fleetmap::vehicle_agent::node
