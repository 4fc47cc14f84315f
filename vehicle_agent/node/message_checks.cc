#include "vehicle_agent/node/message_checks.h"

namespace fleetmap::vehicle_agent::node {

void MessageChecks::Malformed(const std::string& channel, const core::Status& why) {
  ++counters_->malformed_messages;
  log_->Once(channel + ": " + core::StatusCodeName(why.code()),
             channel + ": bad message dropped: " + why.ToString());
}

bool MessageChecks::OurVehicle(const std::string& channel, const std::string& vehicle_id) {
  if (vehicle_id == vehicle_id_) return true;
  ++counters_->wrong_vehicle;
  // A hostile or broken sender's id is cut short: it goes into the log as is.
  log_->Once(channel + ": wrong vehicle",
             channel + ": message names vehicle '" + vehicle_id.substr(0, 64) + "': dropped");
  return false;
}

}  // namespace fleetmap::vehicle_agent::node
