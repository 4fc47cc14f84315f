#include "eval/recording/recorded_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <optional>

#include "auth/replay_window.h"
#include "auth/trailer.h"
#include "auth/verifier.h"
#include "core/map/map_replica.h"
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/status_counter.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::eval::recording {
namespace {

struct Event {
  int64_t wall_utime = 0;
  int order = 0;  // keeps the logger's order among equal stamps
  std::string channel;
  std::vector<uint8_t> data;
};

core::Status ReadLog(const std::string& path, std::vector<Event>& events) {
  lcm::LogFile log(path, "r");
  if (!log.good()) return core::NotFound("cannot open LCM log " + path);
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    Event ev;
    ev.wall_utime = e->timestamp;
    ev.order = static_cast<int>(events.size());
    ev.channel = e->channel;
    const auto* bytes = static_cast<const uint8_t*>(e->data);
    ev.data.assign(bytes, bytes + e->datalen);
    events.push_back(std::move(ev));
  }
  return core::OkStatus();
}

// A message's LCM encoding, without its trailer once attributed.
struct Payload {
  const void* data = nullptr;
  int size = 0;
};

// What the uplink said about one temporary map.
struct TempMapSeen {
  int64_t first_tile_wall_utime = 0;
  core::Pose2 anchor, grid_origin;
  double start_s = 0.0, end_s = 0.0;  // simulated
};

class Reader {
 public:
  Reader(const sim::World& world, const RecordedRunOptions& options)
      : world_(world), options_(options), verifier_(options.fleet_key) {
    for (size_t i = 0; i < world.scenario().vehicles.size(); ++i)
      vehicle_index_[world.scenario().vehicles[i].id] = i;
    // Version 0 is the static map, as the aggregator loads it.
    record_.run.RecordVersion(world.static_map());
    SeedStaticMap();
  }

  void Handle(const Event& e) {
    Payload p{e.data.data(), static_cast<int>(e.data.size())};
    const std::optional<std::string> owner =
        lcmtypes::ChannelOwner(e.channel, options_.aggregator_sender);
    if (owner) {
      const char* refused = Attribute(e, *owner, &p);
      if (refused != nullptr) return (void)++record_.fleet.messages_refused[refused];
      ++record_.fleet.attributed_messages;
    }
    ChannelTraffic& t = record_.fleet.traffic[e.channel];
    ++t.messages;
    t.bytes += static_cast<int64_t>(e.data.size());
    if (e.channel == lcmtypes::kTempMapAckChannel) return;
    if (lcmtypes::IsTempMapTileChannel(e.channel)) return OnTempMapTile(e, p);
    if (e.channel == lcmtypes::kMergeReportChannel) return OnMergeReport(e, p);
    if (e.channel == lcmtypes::kMapKeyframeChannel || e.channel == lcmtypes::kMapDeltaChannel)
      return OnMapTile(e, p);
    if (lcmtypes::HasPrefix(e.channel, lcmtypes::kDivergencePrefix)) return OnDivergence(p);
    if (lcmtypes::HasPrefix(e.channel, lcmtypes::kPosePrefix)) return OnPose(e, p);
    if (lcmtypes::HasPrefix(e.channel, lcmtypes::kAgentStatusPrefix)) return OnAgentStatus(e, p);
  }

  RecordedRun Finish(int64_t first_wall, int64_t last_wall) {
    record_.fleet.wall_span_s = (last_wall - first_wall) * 1e-6;
    record_.fleet.rate_span_s =
        options_.duration_s > 0 ? options_.duration_s : record_.fleet.wall_span_s;
    record_.fleet.final_version = replica_.has_map() ? replica_.version() : 0;
    // Each accepted merge: from its first tile to the last vehicle holding its version.
    for (const auto& [version, closed_wall] : merge_closed_wall_) {
      int64_t held = 0;
      bool everywhere = !vehicle_index_.empty();
      for (const auto& [id, index] : vehicle_index_) {
        (void)index;
        const auto& firsts = version_first_wall_[id];
        const auto it = firsts.lower_bound(version);
        if (it == firsts.end()) {
          everywhere = false;
          break;
        }
        held = std::max(held, it->second);
      }
      if (everywhere)
        record_.fleet.change_latency_s.push_back(std::max<int64_t>(0, held - closed_wall) * 1e-6);
      else
        ++record_.fleet.changes_not_everywhere;
    }
    return std::move(record_);
  }

 private:
  double SimTime(int64_t utime) const { return lcmtypes::FromUtime(utime) - options_.epoch_s; }

  // Null if the message is `owner`'s (and `p` then holds it without its trailer), else the
  // reason it is not.
  const char* Attribute(const Event& e, const std::string& owner, Payload* p) {
    if (verifier_.enabled()) {
      auth::Opened opened;
      const auth::Verdict v = verifier_.Open(e.channel, p->data, p->size, owner, &opened);
      if (v != auth::Verdict::kAccepted) return auth::VerdictName(v);
      *p = {opened.data, opened.size};
      return nullptr;
    }
    // Without the key a trailer's MAC cannot be checked: its name and number are taken as
    // an identity trailer's are.
    auth::Trailer t;
    if (!auth::SplitTrailer(p->data, static_cast<size_t>(p->size), &t)) return "unnamed";
    if (!owner.empty() && t.sender != owner) return auth::VerdictName(auth::Verdict::kWrongSender);
    if (!windows_[t.sender].Accept(t.seq)) return auth::VerdictName(auth::Verdict::kReplayed);
    *p = {t.payload, static_cast<int>(t.payload_size)};
    return nullptr;
  }

  template <typename T>
  std::optional<T> DecodeOrCount(const Payload& p) {
    auto m = lcmtypes::Decode<T>(p.data, p.size);
    if (!m.ok()) {
      ++record_.fleet.malformed_messages;
      return std::nullopt;
    }
    return std::move(m).value();
  }

  void SeedStaticMap() {
    const core::OccupancyGrid& map = world_.static_map();
    const core::TileOptions tiles;
    const std::vector<core::EncodedTile> all = core::EncodeAllTiles(map, tiles);
    for (size_t i = 0; i < all.size(); ++i) {
      core::KeyframeTile k;
      k.version = 0;
      k.geometry = map.geometry();
      k.tile_size_cells = tiles.tile_size_cells;
      k.index = static_cast<int32_t>(i);
      k.count = static_cast<int32_t>(all.size());
      k.tile = all[i].index;
      k.frame = all[i].frame;
      (void)replica_.AddKeyframeTile(k);
    }
  }

  void OnTempMapTile(const Event& e, const Payload& p) {
    auto msg = DecodeOrCount<fleetmap::tempmap_tile_t>(p);
    if (!msg) return;
    auto tile = lcmtypes::FromMessage(*msg);
    if (!tile.ok()) {
      ++record_.fleet.map_messages_refused;
      return;
    }
    const auto key = std::make_pair(tile->vehicle_id, tile->sequence);
    if (temp_maps_.count(key)) return;
    TempMapSeen& seen = temp_maps_[key];
    seen.first_tile_wall_utime = e.wall_utime;
    seen.anchor = tile->anchor_in_map;
    seen.grid_origin = tile->grid_origin;
    seen.start_s = tile->start_s - options_.epoch_s;
    seen.end_s = tile->end_s - options_.epoch_s;
  }

  void OnMergeReport(const Event& e, const Payload& p) {
    auto msg = DecodeOrCount<fleetmap::merge_report_t>(p);
    if (!msg) return;
    const auto seen = temp_maps_.find(std::make_pair(msg->vehicle_id, msg->tempmap_seq));
    const auto vehicle = vehicle_index_.find(msg->vehicle_id);
    if (seen == temp_maps_.end() || vehicle == vehicle_index_.end()) {
      ++record_.fleet.map_messages_refused;  // a report about a map nobody logged sending
      return;
    }
    const TempMapSeen& m = seen->second;
    eval::MergeRecord r;
    r.vehicle_id = msg->vehicle_id;
    r.tempmap_seq = msg->tempmap_seq;
    r.closed_s = m.end_s;
    // Simulated time of the merge: the map's end plus the wall-clock time it took.
    r.merged_s = m.end_s + (e.wall_utime - m.first_tile_wall_utime) * 1e-6;
    r.accepted = msg->accepted;
    r.reason = msg->reason;
    // The report's dx, dy, dtheta move the anchor (merge_report_t): the placed anchor.
    const core::Pose2 placed(m.anchor.x_m + msg->dx_m, m.anchor.y_m + msg->dy_m,
                             core::NormalizeAngle(m.anchor.theta_rad + msg->dtheta_rad));
    r.placed_origin = placed * m.grid_origin;
    r.anchor_origin = m.anchor * m.grid_origin;
    r.true_origin = world_.VehicleStateAt(vehicle->second, m.start_s).pose * m.grid_origin;
    for (const fleetmap::line_match_t& l : msg->matches)
      r.lines.push_back({l.temp_line_id, l.static_line_id, l.distance_diff_px, l.angle_diff_deg});
    r.cells_added = msg->cells_added;
    r.cells_removed = msg->cells_removed;
    record_.run.merges.push_back(r);
    if (msg->accepted && !merge_closed_wall_.count(msg->new_version))
      merge_closed_wall_[msg->new_version] = m.first_tile_wall_utime;
  }

  void OnMapTile(const Event& e, const Payload& p) {
    const int32_t before = replica_.version();
    core::Result<bool> applied = false;
    if (e.channel == lcmtypes::kMapKeyframeChannel) {
      auto msg = DecodeOrCount<fleetmap::map_keyframe_t>(p);
      if (!msg) return;
      auto tile = lcmtypes::FromMessage(*msg);
      if (!tile.ok()) return (void)++record_.fleet.map_messages_refused;
      // A keyframe of a version we already hold brings nothing new.
      if (tile->version <= replica_.version()) return;
      applied = replica_.AddKeyframeTile(*tile);
    } else {
      auto msg = DecodeOrCount<fleetmap::map_delta_t>(p);
      if (!msg) return;
      auto tile = lcmtypes::FromMessage(*msg);
      if (!tile.ok()) return (void)++record_.fleet.map_messages_refused;
      if (tile->base_version < replica_.version()) return;  // a resend of an old delta
      applied = replica_.AddDeltaTile(*tile);
    }
    if (!applied.ok()) return (void)++record_.fleet.map_messages_refused;
    // A delta that does not fit drops the map (version -1): nothing to record then.
    if (replica_.has_map() && replica_.version() != before)
      record_.run.RecordVersion(replica_.map());
  }

  void OnDivergence(const Payload& p) {
    auto msg = DecodeOrCount<fleetmap::divergence_t>(p);
    if (!msg) return;
    const double t = SimTime(msg->utime);
    double& next = next_divergence_s_[msg->vehicle_id];
    if (t < next) return;
    next = t + options_.divergence_period_s;
    record_.run.divergence.push_back({msg->vehicle_id, t, msg->w_avg, msg->w_slow, msg->w_fast,
                                      msg->d, msg->state == fleetmap::divergence_t::BUILDING});
  }

  void OnAgentStatus(const Event& e, const Payload& p) {
    auto msg = DecodeOrCount<fleetmap::status_t>(p);
    if (!msg) return;
    const int64_t cpu_us = lcmtypes::StatusCounter(*msg, "cpu_time_us").value_or(-1);
    const int64_t rss_kb = lcmtypes::StatusCounter(*msg, "rss_kb").value_or(-1);
    if (cpu_us < 0) return;  // an agent that does not report its usage
    auto [it, first] = record_.fleet.agent_usage.try_emplace(msg->process);
    AgentUsage& u = it->second;
    if (first) {
      u.first_wall_utime = e.wall_utime;
      u.first_cpu_us = cpu_us;
    }
    u.last_wall_utime = e.wall_utime;
    u.last_cpu_us = cpu_us;
    u.max_rss_kb = std::max(u.max_rss_kb, rss_kb);
  }

  void OnPose(const Event& e, const Payload& p) {
    auto msg = DecodeOrCount<fleetmap::pose_with_covariance_t>(p);
    if (!msg) return;
    auto pose = lcmtypes::FromMessage(*msg);
    const auto vehicle = vehicle_index_.find(msg->vehicle_id);
    if (!pose.ok() || vehicle == vehicle_index_.end()) return;
    record_.fleet.last_version_by_vehicle[msg->vehicle_id] = msg->map_version;
    auto& firsts = version_first_wall_[msg->vehicle_id];
    if (firsts.empty() || firsts.rbegin()->first < msg->map_version)
      firsts[msg->map_version] = e.wall_utime;
    const double t = SimTime(msg->utime);
    double& next = next_pose_s_[msg->vehicle_id];
    if (t < next) return;
    next = t + options_.pose_period_s;
    record_.run.poses.push_back(
        {msg->vehicle_id, t, pose->pose_in_map, world_.VehicleStateAt(vehicle->second, t).pose});
  }

  const sim::World& world_;
  const RecordedRunOptions options_;
  std::map<std::string, size_t> vehicle_index_;
  core::MapReplica replica_;
  std::map<std::pair<std::string, int32_t>, TempMapSeen> temp_maps_;
  std::map<int32_t, int64_t> merge_closed_wall_;  // new version -> its map's first tile
  // Per vehicle: map version -> the first wall time a POSE_ carried it (increasing only).
  std::map<std::string, std::map<int32_t, int64_t>> version_first_wall_;
  std::map<std::string, double> next_divergence_s_, next_pose_s_;
  RecordedRun record_;
  auth::Verifier verifier_;                            // with the fleet key, if there is one
  std::map<std::string, auth::ReplayWindow> windows_;  // without it: per named sender
};

}  // namespace

core::Result<RecordedRun> ReadRecordedRun(const std::vector<std::string>& log_paths,
                                          const sim::World& world,
                                          const RecordedRunOptions& options) {
  if (log_paths.empty()) return core::InvalidArgument("no LCM log to read");
  std::vector<Event> events;
  for (const std::string& path : log_paths) FLEETMAP_RETURN_IF_ERROR(ReadLog(path, events));
  if (events.empty()) return core::InvalidArgument("the LCM logs hold no message");
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
    return a.wall_utime != b.wall_utime ? a.wall_utime < b.wall_utime : a.order < b.order;
  });
  Reader reader(world, options);
  for (const Event& e : events) reader.Handle(e);
  RecordedRun run = reader.Finish(events.front().wall_utime, events.back().wall_utime);
  int refused = 0;
  for (const auto& [reason, n] : run.fleet.messages_refused) refused += n;
  if (run.fleet.attributed_messages == 0 && refused > 0) {
    return core::FailedPrecondition(
        "none of the " + std::to_string(refused) +
        " messages on the fleet's channels can be attributed to its sender (" +
        (options.fleet_key ? "is it this fleet's key?"
                           : "recorded from processes that do not "
                             "name themselves?") +
        "): nothing to score");
  }
  return run;
}

}  // namespace fleetmap::eval::recording

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
