// The multicast groups a node talks on (docs/channels.md): a vehicle's own sensor traffic,
// the uplink from the vehicles to the aggregator and the downlink back. The agent uses all
// three, the aggregator the uplink and the downlink.
#pragma once

namespace fleetmap::edge {

enum class Link { kSensor, kUplink, kDownlink };

// "sensor", "uplink", "downlink".
const char* LinkName(Link link);

}  // namespace fleetmap::edge
