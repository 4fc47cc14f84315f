// How the aggregator node talks to the outside without owning a socket: messages come in as
// (channel, bytes, time) and go out through a Publisher, log lines through a LogSink (both
// shared with the agent's node, edge/). Vehicles send on the uplink (TEMPMAP_<id>,
// MAP_REQUEST), the aggregator answers on the downlink. The process binds these to LCM
// (aggregator_links.h), a replay to nothing, tests to memory.
#pragma once

#include "edge/cause_log.h"
#include "edge/link.h"
#include "edge/log_sink.h"
#include "edge/publisher.h"

namespace fleetmap::aggregator::node {

using edge::CauseLog;
using edge::Link;
using edge::LinkName;
using edge::LogLevel;
using edge::LogSink;
using edge::Publisher;

}  // namespace fleetmap::aggregator::node
