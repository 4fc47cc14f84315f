// The last STATUS_<process> heartbeat of every process in a recorded run: the agents'
// temporary maps closed, delivered and resent, the aggregator's tiles and merges
// (docs/agent_process.md, docs/aggregator_process.md list the counters).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ops/lan/lan_log.h"

namespace fleetmap::ops::lan {

struct ProcessStatus {
  int64_t utime = 0;  // the heartbeat's send time
  int32_t map_version = -1;
  std::string state;
  std::map<std::string, int64_t> counters;
  int heartbeats = 0;  // STATUS_ messages logged for this process
};

struct StatusSummary {
  std::map<std::string, ProcessStatus> processes;  // by the message's `process` field
  int malformed = 0;                               // STATUS_ messages that did not decode
};

// Keeps, per process, the heartbeat with the latest send time, among those sent before
// `until_utime` (microseconds since the Unix epoch; 0: all). The experiment stops the
// aggregator first, then the agents: their last heartbeats, sent at their stop, would count
// the map they flush then as closed and pending.
StatusSummary SummarizeStatus(const std::vector<LogMessage>& messages, int64_t until_utime = 0);

// `status.<process>.<counter> value count` lines, plus map_version, heartbeats and, for all
// agents together, `status.agents.<counter>` sums of the counters below (see the .cc).
std::string StatusFigureLines(const StatusSummary& summary);

}  // namespace fleetmap::ops::lan
