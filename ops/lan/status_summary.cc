#include "ops/lan/status_summary.h"

#include "auth/trailer.h"
#include "fleetmap/status_t.hpp"
#include "lcmtypes/convert.h"

namespace fleetmap::ops::lan {
namespace {

// Agent counters summed over the fleet: what the experiment reports per run.
constexpr const char* kSummedAgentCounters[] = {
    "tempmaps_closed", "tempmaps_dropped",     "tempmaps_pending", "tiles_sent", "tiles_resent",
    "maps_merged",     "maps_rejected",        "maps_duplicate",   "acks",       "scans",
    "scans_skipped",   "map_versions_applied", "keyframe_requests"};

}  // namespace

StatusSummary SummarizeStatus(const std::vector<LogMessage>& messages, int64_t until_utime) {
  StatusSummary summary;
  for (const LogMessage& m : messages) {
    if (!lcmtypes::HasPrefix(m.channel, lcmtypes::kStatusPrefix)) continue;
    auto status = lcmtypes::Decode<fleetmap::status_t>(
        m.data.data(), int(auth::PayloadSize(m.data.data(), m.data.size())));
    if (!status.ok() || status->counter_names.size() != status->counter_values.size()) {
      ++summary.malformed;
      continue;
    }
    if (until_utime > 0 && status->utime >= until_utime) continue;
    ProcessStatus& p = summary.processes[status->process];
    ++p.heartbeats;
    if (p.heartbeats > 1 && status->utime < p.utime) continue;
    p.utime = status->utime;
    p.map_version = status->map_version;
    p.state = status->state;
    p.counters.clear();
    for (size_t i = 0; i < status->counter_names.size(); ++i)
      p.counters[status->counter_names[i]] = status->counter_values[i];
  }
  return summary;
}

std::string StatusFigureLines(const StatusSummary& summary) {
  std::string out;
  std::map<std::string, int64_t> agent_sums;
  int agents = 0;
  for (const auto& [process, p] : summary.processes) {
    const std::string prefix = "status." + process + ".";
    out += prefix + "map_version " + std::to_string(p.map_version) + " version\n";
    out += prefix + "heartbeats " + std::to_string(p.heartbeats) + " count\n";
    for (const auto& [name, value] : p.counters)
      out += prefix + name + " " + std::to_string(value) + " count\n";
    if (process.rfind("agent_", 0) != 0) continue;
    ++agents;
    for (const char* name : kSummedAgentCounters) {
      const auto it = p.counters.find(name);
      if (it != p.counters.end()) agent_sums[name] += it->second;
    }
  }
  out += "status.agents.count " + std::to_string(agents) + " count\n";
  for (const auto& [name, value] : agent_sums)
    out += "status.agents." + name + " " + std::to_string(value) + " count\n";
  out += "status.malformed " + std::to_string(summary.malformed) + " count\n";
  return out;
}

}  // namespace fleetmap::ops::lan
