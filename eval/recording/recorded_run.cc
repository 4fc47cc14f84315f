#include "eval/recording/recorded_run.h"

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/map/map_replica.h"
#include "eval/anchor_consistency.h"
#include "eval/recording/lcm_log_events.h"
#include "eval/recording/sender_attribution.h"
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/status_counter.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::eval::recording {
namespace {

// What the uplink said about one temporary map.
struct TempMapSeen {
  int64_t first_tile_wall_utime = 0;
  core::Pose2 anchor, grid_origin;
  std::optional<Eigen::Matrix3d> anchor_covariance;
  double start_s = 0.0, end_s = 0.0;  // simulated
};

class Reader {
 public:
  Reader(const sim::World& world, const RecordedRunOptions& options)
      : world_(world), options_(options), attribution_(options.fleet_key) {
    for (size_t i = 0; i < world.scenario().vehicles.size(); ++i)
      vehicle_index_[world.scenario().vehicles[i].id] = i;
    // Version 0 is the static map, as the aggregator loads it.
    record_.run.RecordVersion(world.static_map());
    SeedStaticMap();
  }

  void Handle(const LoggedEvent& e) {
    Payload p{e.data.data(), static_cast<int>(e.data.size())};
    const std::optional<std::string> owner =
        lcmtypes::ChannelOwner(e.channel, options_.aggregator_sender);
    if (owner) {
      const char* refused = attribution_.Attribute(e.channel, *owner, &p);
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

  void OnTempMapTile(const LoggedEvent& e, const Payload& p) {
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
    seen.anchor_covariance = tile->anchor_covariance;
    seen.start_s = tile->start_s - options_.epoch_s;
    seen.end_s = tile->end_s - options_.epoch_s;
  }

  void OnMergeReport(const LoggedEvent& e, const Payload& p) {
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
    const core::Pose2 true_anchor = world_.VehicleStateAt(vehicle->second, m.start_s).pose;
    r.true_origin = true_anchor * m.grid_origin;
    if (m.anchor_covariance)
      r.anchor_nees = AnchorNees(m.anchor, *m.anchor_covariance, true_anchor);
    for (const fleetmap::line_match_t& l : msg->matches)
      r.lines.push_back({l.temp_line_id, l.static_line_id, l.distance_diff_px, l.angle_diff_deg});
    r.cells_added = msg->cells_added;
    r.cells_removed = msg->cells_removed;
    record_.run.merges.push_back(r);
    if (msg->accepted && !merge_closed_wall_.count(msg->new_version))
      merge_closed_wall_[msg->new_version] = m.first_tile_wall_utime;
  }

  void OnMapTile(const LoggedEvent& e, const Payload& p) {
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

  void OnAgentStatus(const LoggedEvent& e, const Payload& p) {
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

  void OnPose(const LoggedEvent& e, const Payload& p) {
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
  SenderAttribution attribution_;
};

}  // namespace

core::Result<RecordedRun> ReadRecordedRun(const std::vector<std::string>& log_paths,
                                          const sim::World& world,
                                          const RecordedRunOptions& options) {
  std::vector<LoggedEvent> events;
  FLEETMAP_ASSIGN_OR_RETURN(events, ReadLogEvents(log_paths));
  Reader reader(world, options);
  for (const LoggedEvent& e : events) reader.Handle(e);
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
