// The node's handling of bad input, shared by every handler: a message that does not decode,
// fails validation or names another vehicle is counted, logged once per cause (CauseLog) and
// dropped, so that a stream of broken messages neither floods the log nor stops the node.
#pragma once

#include <optional>
#include <string>

#include "core/result.h"
#include "lcmtypes/convert.h"
#include "vehicle_agent/node/agent_counters.h"
#include "vehicle_agent/node/node_io.h"

namespace fleetmap::vehicle_agent::node {

class MessageChecks {
 public:
  // `log` and `counters` (malformed_messages, wrong_vehicle) outlive the checks.
  MessageChecks(std::string vehicle_id, CauseLog* log, AgentNodeCounters* counters)
      : vehicle_id_(std::move(vehicle_id)), log_(log), counters_(counters) {}

  // The message of type T in `data`, or nothing when it does not decode (counted as malformed).
  template <typename T>
  std::optional<T> Decode(const std::string& channel, const void* data, int size) {
    core::Result<T> m = lcmtypes::Decode<T>(data, size);
    if (!m.ok()) {
      Malformed(channel, m.status());
      return std::nullopt;
    }
    return std::move(m).value();
  }
  // A message on `channel` that is dropped for `why`.
  void Malformed(const std::string& channel, const core::Status& why);
  // Whether a message on `channel` naming `vehicle_id` is for this vehicle; counted when not.
  bool OurVehicle(const std::string& channel, const std::string& vehicle_id);

 private:
  const std::string vehicle_id_;
  CauseLog* const log_;
  AgentNodeCounters* const counters_;
};

}  // namespace fleetmap::vehicle_agent::node
