// How the aggregator node talks to the outside without owning a socket: messages come in as
// (channel, bytes, time) and go out through a Publisher, log lines through a LogSink. The
// process binds these to LCM (lcm_links.h), a replay to nothing, tests to memory.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace fleetmap::aggregator::node {

// The two multicast groups of the map transport (lcmtypes/convert.h): vehicles send on the
// uplink (TEMPMAP_<id>, MAP_REQUEST), the aggregator answers on the downlink.
enum class Link { kUplink, kDownlink };
const char* LinkName(Link link);  // "uplink", "downlink"

class Publisher {
 public:
  virtual ~Publisher() = default;
  // Sends one encoded message; returns false when the transport refused it (counted).
  virtual bool Publish(Link link, const std::string& channel,
                       const std::vector<uint8_t>& bytes) = 0;
};

enum class LogLevel { kInfo, kWarning };
using LogSink = std::function<void(LogLevel level, const std::string& line)>;

}  // namespace fleetmap::aggregator::node
