// How the agent node talks to the outside without owning a socket: messages come in as
// (link, channel, bytes) and go out through a Publisher, log lines through a LogSink. The
// process binds these to LCM (lcm_links.h); tests bind them to memory.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace fleetmap::vehicle_agent::node {

// The three multicast groups an agent uses (lcmtypes/convert.h): the vehicle's own sensor
// traffic, the uplink to the aggregator and the downlink from it.
enum class Link { kSensor, kUplink, kDownlink };
const char* LinkName(Link link);  // "sensor", "uplink", "downlink"

class Publisher {
 public:
  virtual ~Publisher() = default;
  // Sends one encoded message; returns false when the transport refused it (counted).
  virtual bool Publish(Link link, const std::string& channel,
                       const std::vector<uint8_t>& bytes) = 0;
};

// A channel the node wants to receive on a link (an exact name, never a pattern).
struct Subscription {
  Link link = Link::kSensor;
  std::string channel;
};

enum class LogLevel { kInfo, kWarning };
using LogSink = std::function<void(LogLevel level, const std::string& line)>;

}  // namespace fleetmap::vehicle_agent::node
