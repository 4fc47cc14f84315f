// How the agent node talks to the outside without owning a socket: messages come in as
// (link, channel, bytes) and go out through a Publisher, log lines through a LogSink (both
// shared with the aggregator's node, edge/). The process binds these to LCM (agent_links.h);
// tests bind them to memory.
#pragma once

#include <string>

#include "edge/cause_log.h"
#include "edge/link.h"
#include "edge/log_sink.h"
#include "edge/publisher.h"

namespace fleetmap::vehicle_agent::node {

using edge::CauseLog;
using edge::Link;
using edge::LinkName;
using edge::LogLevel;
using edge::LogSink;
using edge::Publisher;

// A channel the node wants to receive on a link (an exact name, never a pattern).
struct Subscription {
  Link link = Link::kSensor;
  std::string channel;
};

}  // namespace fleetmap::vehicle_agent::node
