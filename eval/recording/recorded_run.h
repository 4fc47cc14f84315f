// A fleet run recorded by lcm-logger (one log per multicast group: sensor, uplink, downlink)
// read back into the evaluation's RunRecord, so that the live system over the network is
// scored exactly like the in-process pipelines, plus what only a network run has: bytes per
// channel, and the latency from a temporary map closing on a vehicle to every vehicle holding
// the change.
//
// Times: the simulator stamps messages with epoch + simulated time (fleetmap-sim --epoch), so
// message stamps minus the epoch are simulated seconds; latencies and rates use the logger's
// receive stamps (wall clock), since the simulator may run faster than real time.
//
// Whose word counts: a message on a channel that belongs to a process (the downlink to the
// aggregator, TEMPMAP_<id>, POSE_<id>, ... to vehicle <id>) is read only if its trailer
// (auth/trailer.h) names that process with a sequence number not seen before, and, with the
// fleet key, only if its MAC is right. Everything else on those channels (another fleet, a
// test tool, a copy of an old message, malformed bytes) is counted by reason and left out,
// so that it changes no figure.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "auth/key.h"
#include "eval/run_record.h"
#include "sim/world.h"

namespace fleetmap::eval::recording {

struct RecordedRunOptions {
  double epoch_s = 0.0;              // what fleetmap-sim added to simulated time, seconds
  double divergence_period_s = 0.1;  // keep one DIVERGENCE_ sample per vehicle per period
  double pose_period_s = 0.5;        // and one POSE_ sample
  // Simulated seconds the run covered: rates per channel are per simulated second (what a
  // fleet sends in real time, whatever the simulator's speed). 0: per wall-clock second.
  double duration_s = 0.0;
  std::string aggregator_sender = "aggregator";  // the aggregator's process name
  std::optional<auth::Key> fleet_key;            // the run's fleet key, if it had one
};

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

struct RecordedRun {
  eval::RunRecord run;
  FleetFigures fleet;
};

// Reads every log (any order; events are merged by receive time). The static map of `world`
// is version 0; MAP_KEYFRAME and MAP_DELTA rebuild every later version as a vehicle would.
// FailedPrecondition when the fleet's channels hold messages but none can be attributed (a
// log of processes that do not name themselves, or read with another fleet's key).
core::Result<RecordedRun> ReadRecordedRun(const std::vector<std::string>& log_paths,
                                          const sim::World& world,
                                          const RecordedRunOptions& options);

}  // namespace fleetmap::eval::recording

namespace fleetmap::eval::recording {
// The fleet figures as `"key": value` pairs for report.json (fleet.bytes_per_s.<CHANNEL>,
// fleet.change_latency_s.*, ...; agent.cpu_percent: CPU of one agent process in % of one core
// over the wall-clock time of the run, the mean over the agents; agent.cpu_percent_realtime:
// the same per simulated second, what an agent costs at real time when the simulator ran
// faster; agent.rss_mb: the largest resident set of any agent), and as figure lines.
std::vector<std::pair<std::string, std::string>> FleetJsonPairs(const FleetFigures& fleet);
std::string FleetFigureLines(const FleetFigures& fleet);
}  // namespace fleetmap::eval::recording
