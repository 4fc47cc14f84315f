// Replays LCM log files (lcm-logger's format, read with lcm::LogFile) into an aggregator
// node: every uplink message (TEMPMAP_<vehicle>, MAP_REQUEST) in the order of its event
// time, as fast as possible, with the event time as the receive time. The node's merges take
// their time from the messages themselves, so a replay rebuilds exactly the map of the run
// that was logged. Several logs are merged by event time (ties: the earlier file first).
#pragma once

#include <csignal>
#include <string>
#include <vector>

#include "aggregator/node/aggregator_node.h"

namespace fleetmap::aggregator::node {

struct ReplayStats {
  int64_t events = 0;                  // read from the logs
  int64_t fed = 0;                     // handed to the node
  int64_t skipped = 0;                 // other channels (downlink, sensors)
  double first_s = 0.0, last_s = 0.0;  // event times of the first and last fed event
};

// True for TEMPMAP_<vehicle> (not TEMPMAP_ACK) and MAP_REQUEST.
bool IsUplinkChannel(const std::string& channel);

// NotFound/IoError naming a log that cannot be opened. Stops early when *stop becomes set.
core::Result<ReplayStats> ReplayLogs(const std::vector<std::string>& paths, AggregatorNode& node,
                                     const volatile std::sig_atomic_t* stop = nullptr);

}  // namespace fleetmap::aggregator::node
