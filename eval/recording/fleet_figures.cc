#include "eval/recording/fleet_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace fleetmap::eval::recording {
namespace {

std::string Num(double v) {
  if (!std::isfinite(v)) return "null";
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const size_t lo = static_cast<size_t>(pos);
  const size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (pos - lo);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> FleetJsonPairs(const FleetFigures& f) {
  std::vector<std::pair<std::string, std::string>> kv;
  // Rates over no time, and a mean over no message, are null (Num of NaN), never 0 or huge.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double span = f.rate_span_s > 0 ? f.rate_span_s : nan;
  for (const auto& [channel, t] : f.traffic)
    kv.emplace_back("fleet.bytes_per_s." + channel, Num(t.bytes / span));
  for (const auto& [channel, t] : f.traffic) {
    kv.emplace_back("fleet.messages_per_s." + channel, Num(t.messages / span));
    kv.emplace_back("fleet.mean_message_bytes." + channel,
                    Num(t.messages > 0 ? double(t.bytes) / t.messages : nan));
  }
  kv.emplace_back("fleet.wall_span_s", Num(f.wall_span_s));
  kv.emplace_back("fleet.rate_span_s", Num(f.rate_span_s));
  kv.emplace_back("fleet.change_latency_s.count", std::to_string(f.change_latency_s.size()));
  kv.emplace_back("fleet.change_latency_s.median", Num(Percentile(f.change_latency_s, 0.5)));
  kv.emplace_back("fleet.change_latency_s.p95", Num(Percentile(f.change_latency_s, 0.95)));
  kv.emplace_back("fleet.change_latency_s.max", Num(Percentile(f.change_latency_s, 1.0)));
  kv.emplace_back("fleet.changes_not_everywhere", std::to_string(f.changes_not_everywhere));
  kv.emplace_back("fleet.final_version", std::to_string(f.final_version));
  int holding = 0;
  for (const auto& [id, v] : f.last_version_by_vehicle) holding += v == f.final_version;
  kv.emplace_back("fleet.vehicles_holding_final_version", std::to_string(holding));
  kv.emplace_back("fleet.malformed_messages", std::to_string(f.malformed_messages));
  kv.emplace_back("fleet.map_messages_refused", std::to_string(f.map_messages_refused));
  int refused = 0;
  for (const auto& [reason, n] : f.messages_refused) refused += n;
  kv.emplace_back("fleet.messages_refused", std::to_string(refused));
  for (const auto& [reason, n] : f.messages_refused)
    kv.emplace_back("fleet.messages_refused." + reason, std::to_string(n));
  // The agents' cost, from their STATUS: only agents seen over more than a few seconds.
  double cpu_share_sum = 0.0, cpu_per_sim_sum = 0.0;
  int agents = 0;
  int64_t rss_kb = -1;
  for (const auto& [process, u] : f.agent_usage) {
    rss_kb = std::max(rss_kb, u.max_rss_kb);
    const double wall_s = (u.last_wall_utime - u.first_wall_utime) * 1e-6;
    if (wall_s < 5.0 || !(f.rate_span_s > 0 && f.wall_span_s > 0)) continue;
    const double cpu_s = (u.last_cpu_us - u.first_cpu_us) * 1e-6;
    cpu_share_sum += cpu_s / wall_s;
    // Simulated seconds in that span: the run's rate span over its wall span.
    cpu_per_sim_sum += cpu_s / (wall_s * f.rate_span_s / f.wall_span_s);
    ++agents;
  }
  if (agents > 0) {
    kv.emplace_back("agent.cpu_percent", Num(100.0 * cpu_share_sum / agents));
    kv.emplace_back("agent.cpu_percent_realtime", Num(100.0 * cpu_per_sim_sum / agents));
  }
  if (rss_kb >= 0) kv.emplace_back("agent.rss_mb", Num(rss_kb / 1024.0));
  return kv;
}

std::string FleetFigureLines(const FleetFigures& f) {
  std::string out;
  for (const auto& [key, value] : FleetJsonPairs(f)) {
    if (value == "null") continue;
    const bool per_s = key.rfind("fleet.bytes_per_s.", 0) == 0;
    const bool rate = key.rfind("fleet.messages_per_s.", 0) == 0;
    const bool size = key.rfind("fleet.mean_message_bytes.", 0) == 0;
    const bool seconds =
        key == "fleet.wall_span_s" || key == "fleet.rate_span_s" ||
        (key.rfind("fleet.change_latency_s.", 0) == 0 && key != "fleet.change_latency_s.count");
    const bool percent = key.rfind("agent.cpu_percent", 0) == 0;
    const char* unit = per_s                   ? "B/s"
                       : rate                  ? "1/s"
                       : size                  ? "B"
                       : seconds               ? "s"
                       : percent               ? "%"
                       : key == "agent.rss_mb" ? "MB"
                                               : "count";
    out += key + " " + value + " " + unit + "\n";
  }
  return out;
}

}  // namespace fleetmap::eval::recording
