// What the agent process costs its vehicle computer, for STATUS_agent_<id>: CPU time used so
// far and resident memory now. Operators (and the demo's report) derive the CPU share from two
// STATUS messages: the difference of cpu_time_us over the difference of their utime.
#pragma once

#include "vehicle_agent/node/agent_counters.h"

namespace fleetmap::vehicle_agent::node {

// {"cpu_time_us", user + system CPU time of this process}, {"rss_kb", resident set now}.
// A value the system does not give is left out rather than reported as 0.
NamedCounters ProcessUsageCounters();

}  // namespace fleetmap::vehicle_agent::node
