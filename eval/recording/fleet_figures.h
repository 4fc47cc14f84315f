// What only a fleet run over the network shows, beyond the evaluation's RunRecord: bytes and
// messages per channel, the latency from a temporary map reaching the aggregator to every
// vehicle holding the change, what was refused and why, and what the agent processes cost;
// and those figures written out for report.json and as figure lines.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace fleetmap::eval::recording {

struct ChannelTraffic {
  int64_t messages = 0;
  int64_t bytes = 0;
};

// What one agent process cost, from its STATUS_agent_<id> counters cpu_time_us and rss_kb.
struct AgentUsage {
  int64_t first_wall_utime = 0, last_wall_utime = 0;  // logger's stamps of the first/last STATUS
  int64_t first_cpu_us = 0, last_cpu_us = 0;          // the process's CPU time then
  int64_t max_rss_kb = 0;                             // largest resident set reported
};

struct FleetFigures {
  double wall_span_s = 0.0;  // first to last logged message, wall-clock seconds
  double rate_span_s = 0.0;  // the denominator of the rates: simulated (or wall) seconds
  std::map<std::string, ChannelTraffic> traffic;  // by channel
  // Per accepted merge: the map's first tile on the uplink -> the last vehicle reporting
  // (POSE_ map_version) the version that merge made. Wall-clock seconds.
  std::vector<double> change_latency_s;
  int changes_not_everywhere = 0;  // accepted merges some vehicle never reported holding
  std::map<std::string, int32_t> last_version_by_vehicle;  // from POSE_
  int32_t final_version = -1;                              // from MAP_DELTA / MAP_KEYFRAME
  int malformed_messages = 0;                              // logged but not decodable
  int map_messages_refused = 0;                            // decodable map tiles refused
  // Messages not attributed to their channel's owner, by reason (auth::VerdictName, and
  // "unnamed": no trailer names a sender); neither read nor counted in `traffic`.
  std::map<std::string, int> messages_refused;
  int attributed_messages = 0;  // messages read on channels that belong to a process
  std::map<std::string, AgentUsage> agent_usage;  // by process (agent_<id>)
};

// The fleet figures as `"key": value` pairs for report.json (fleet.bytes_per_s.<CHANNEL>,
// fleet.change_latency_s.*, ...; agent.cpu_percent: CPU of one agent process in % of one core
// over the wall-clock time of the run, the mean over the agents; agent.cpu_percent_realtime:
// the same per simulated second, what an agent costs at real time when the simulator ran
// faster; agent.rss_mb: the largest resident set of any agent), and as figure lines.
std::vector<std::pair<std::string, std::string>> FleetJsonPairs(const FleetFigures& fleet);
std::string FleetFigureLines(const FleetFigures& fleet);

}  // namespace fleetmap::eval::recording
