#include "vehicle_agent/node/agent_node.h"

#include <algorithm>

#include "fleetmap/map_candidates_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::vehicle_agent::node {
namespace {

const std::string kAggregatorStatus = lcmtypes::StatusChannel("aggregator");

}  // namespace

core::Result<std::unique_ptr<AgentNode>> AgentNode::Create(
    AgentNodeOptions options, Publisher* publisher, LogSink log,
    std::optional<core::OccupancyGrid> static_map, double now_s) {
  const StoredSequence stored = SequenceStore(options.outbox.state_dir).Load();
  options.pipeline.first_sequence = stored.next;
  if (options.initial_pose == InitialPoseSource::kGlobal)
    options.pipeline.localizer.initial_pose_mode = InitialPoseMode::kGlobal;
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  std::unique_ptr<AgentNode> node(new AgentNode(std::move(options), publisher, log, now_s));
  node->uplink_.StartNumberingAt(stored.next);
  if (!stored.issue.ok()) {
    node->log_.Warning("temporary-map numbering: " + stored.issue.ToString() + "; going on from " +
                       std::to_string(stored.next));
  }
  if (static_map)
    FLEETMAP_RETURN_IF_ERROR(node->maps_.Seed(std::move(*static_map), 0).WithContext("--map"));
  node->pose_.LoadKept();
  node->uplink_.ReloadPending(now_s);
  return node;
}

AgentNode::AgentNode(AgentNodeOptions options, Publisher* publisher, LogSink log, double now_s)
    : options_(std::move(options)),
      log_(std::move(log)),
      checks_(options_.pipeline.vehicle_id, &log_, &counters_),
      sender_(options_, publisher, &log_, &counters_),
      pipeline_(options_.pipeline),
      uplink_(options_.outbox, options_.uplink_pacer, &log_, &counters_),
      maps_(options_.map, &log_, &counters_),
      pose_(options_, &pipeline_, &log_, &checks_, &counters_),
      intake_(options_.pipeline.vehicle_id, options_.queue, &checks_),
      next_status_s_(now_s),
      verifier_(options_.fleet_key) {}

std::vector<Subscription> AgentNode::Subscriptions() const {
  const std::string& id = options_.pipeline.vehicle_id;
  std::vector<Subscription> subs;
  if (options_.scans_from_lcm) subs.push_back({Link::kSensor, lcmtypes::ScanChannel(id)});
  if (options_.odometry_from_lcm) subs.push_back({Link::kSensor, lcmtypes::OdomChannel(id)});
  if (options_.use_external_pose)
    subs.push_back({Link::kSensor, lcmtypes::ExternalPoseChannel(id)});
  for (const char* channel : {lcmtypes::kTempMapAckChannel, lcmtypes::kMapDeltaChannel,
                              lcmtypes::kMapKeyframeChannel, lcmtypes::kMapCandidatesChannel})
    subs.push_back({Link::kDownlink, channel});
  subs.push_back({Link::kDownlink, kAggregatorStatus});
  return subs;
}

// ---- input ----------------------------------------------------------------------------------

void AgentNode::OnMessage(Link link, const std::string& channel, const void* data, int size,
                          double now_s) {
  const std::string& id = options_.pipeline.vehicle_id;
  // A shared LCM instance (the same URL for two links) delivers more than we asked for.
  if (link == Link::kSensor) {
    if (channel == lcmtypes::ScanChannel(id) && options_.scans_from_lcm) {
      ++counters_.messages;
      intake_.OnScan(data, size);
    } else if (channel == lcmtypes::OdomChannel(id) && options_.odometry_from_lcm) {
      ++counters_.messages;
      intake_.OnOdometry(data, size);
    } else if (channel == lcmtypes::ExternalPoseChannel(id) && options_.use_external_pose) {
      ++counters_.messages;
      intake_.OnExternalPose(data, size);
    }
    return;
  }
  if (link != Link::kDownlink) return;
  if (channel != lcmtypes::kTempMapAckChannel && channel != lcmtypes::kMapDeltaChannel &&
      channel != lcmtypes::kMapKeyframeChannel && channel != lcmtypes::kMapCandidatesChannel &&
      channel != kAggregatorStatus) {
    return;
  }
  auth::Opened opened;
  const auth::Verdict verdict =
      verifier_.Open(channel, data, size, options_.aggregator_sender, &opened);
  if (verdict != auth::Verdict::kAccepted) {
    ++counters_.messages;
    ++counters_.auth_refused;
    log_.Once(channel + ": auth " + auth::VerdictName(verdict),
              channel + ": " + auth::RefusalText(verdict));
    return;
  }
  data = opened.data;
  size = opened.size;
  if (channel == lcmtypes::kTempMapAckChannel) {
    OnAck(data, size);
  } else if (channel == lcmtypes::kMapDeltaChannel) {
    OnDelta(data, size);
  } else if (channel == lcmtypes::kMapKeyframeChannel) {
    OnKeyframe(data, size);
  } else if (channel == lcmtypes::kMapCandidatesChannel) {
    OnCandidates(data, size);
  } else if (channel == kAggregatorStatus) {
    OnAggregatorStatus(data, size, now_s);
  } else {
    return;
  }
  ++counters_.messages;
}

void AgentNode::OnDriverScan(const core::LaserScan& scan) { intake_.OnDriverScan(scan); }

void AgentNode::OnDriverOdometry(const core::OdometrySample& odom) {
  intake_.OnDriverOdometry(odom);
}

void AgentNode::OnAck(const void* data, int size) {
  auto m = checks_.Decode<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel, data, size);
  if (!m || m->vehicle_id != options_.pipeline.vehicle_id) return;  // others' acks: not ours
  const core::Status applied = uplink_.OnAck(*m);
  if (!applied.ok()) checks_.Malformed(lcmtypes::kTempMapAckChannel, applied);
}

void AgentNode::OnDelta(const void* data, int size) {
  auto m = checks_.Decode<fleetmap::map_delta_t>(lcmtypes::kMapDeltaChannel, data, size);
  if (!m) return;
  core::Result<core::DeltaTile> tile = lcmtypes::FromMessage(*m);
  if (!tile.ok()) return checks_.Malformed(lcmtypes::kMapDeltaChannel, tile.status());
  maps_.OnDeltaTile(*tile);
}

void AgentNode::OnKeyframe(const void* data, int size) {
  auto m = checks_.Decode<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel, data, size);
  if (!m) return;
  core::Result<core::KeyframeTile> tile = lcmtypes::FromMessage(*m);
  if (!tile.ok()) return checks_.Malformed(lcmtypes::kMapKeyframeChannel, tile.status());
  maps_.OnKeyframeTile(*tile);
}

void AgentNode::OnAggregatorStatus(const void* data, int size, double now_s) {
  auto m = checks_.Decode<fleetmap::status_t>(kAggregatorStatus, data, size);
  if (!m) return;
  if (m->map_version >= 0) maps_.OnRemoteVersion(m->map_version, now_s);
  uplink_.OnAggregatorStatus(*m, now_s);
}

void AgentNode::OnCandidates(const void* data, int size) {
  auto m = checks_.Decode<fleetmap::map_candidates_t>(lcmtypes::kMapCandidatesChannel, data, size);
  if (!m) return;
  auto set = candidates_.Add(*m);
  if (!set.ok()) return checks_.Malformed(lcmtypes::kMapCandidatesChannel, set.status());
  if (*set) pipeline_.SetCandidates(**set);
}

// ---- processing -----------------------------------------------------------------------------

void AgentNode::Tick(double now_s) {
  ApplyMap();
  for (const SensorInput& input : intake_.TakeAll()) Process(input, now_s);
  if (const std::optional<int32_t> have = maps_.RequestDue(now_s))
    sender_.SendMapRequest(*have, maps_.request_tiles(), now_s);
  SendTiles(now_s);
  SendCandidates(now_s);
  if (now_s >= next_status_s_) {
    SendStatus(now_s);
    // Not now_s + period: a late tick must not shift every later heartbeat.
    next_status_s_ = std::max(next_status_s_ + options_.status_period_s, now_s);
  }
}

void AgentNode::ApplyMap() {
  if (maps_.Apply(pipeline_)) pose_.OnFirstMap();
}

void AgentNode::Process(const SensorInput& input, double now_s) {
  if (const auto* scan = std::get_if<core::LaserScan>(&input)) return ProcessScan(*scan, now_s);
  if (const auto* odom = std::get_if<core::OdometrySample>(&input)) {
    ++counters_.odometry;
    pipeline_.AddOdometry(*odom);
    if (odom->Validate().ok()) pose_.OnOdometry(odom->pose_in_odom);
    return;
  }
  ++counters_.external_poses;
  pose_.OnExternalPose(std::get<ExternalPoseInput>(input).pose);
}

void AgentNode::ProcessScan(const core::LaserScan& scan, double now_s) {
  if (!maps_.in_use()) {
    ++counters_.scans_waiting_for_map;
    return;
  }
  if (!pose_.initialized()) {
    ++counters_.scans_waiting_for_pose;
    return;
  }
  const AgentStep step = pipeline_.AddScan(scan);
  ++counters_.scans;
  building_ = step.building;
  ReportLocalization(step.localization);
  pose_.OnStep(step, now_s);
  // The map being built, or the last one: sequences are handed out one per started map.
  const auto sequence = static_cast<int32_t>(options_.pipeline.first_sequence - 1 +
                                             pipeline_.counters().temp_maps_started);
  sender_.SendStep(scan, step, sequence);
  if (step.closed_map) uplink_.Keep(*step.closed_map, now_s);
}

void AgentNode::ReportLocalization(const LocalizerStats& stats) {
  counters_.tempmaps_dropped_lost = pipeline_.counters().temp_maps_dropped;
  if (stats.relocalized) {
    log_.Warning(
        "lost: the map has not explained the scans for a while and a search of the whole map "
        "found poses that fit them clearly better; following those");
  }
  if (stats.lost == (counters_.lost != 0)) return;
  counters_.lost = stats.lost;
  if (!stats.lost) log_.Info("localized again: the map explains the scans");
}

void AgentNode::Shutdown(double now_s) {
  ApplyMap();
  for (const SensorInput& input : intake_.TakeAll()) Process(input, now_s);
  if (std::optional<core::TempMap> last = pipeline_.Flush(now_s)) uplink_.Keep(*last, now_s);
  pose_.KeepLast(now_s);
  building_ = false;
  SendTiles(now_s, /*all=*/true);  // at exit: what is queued goes now (it is on disk too)
  SendStatus(now_s);
}

void AgentNode::Drain(double now_s) {
  ApplyMap();
  SendTiles(now_s, /*all=*/true);
}

// ---- output ---------------------------------------------------------------------------------

void AgentNode::SendTiles(double now_s, bool all) {
  sender_.SendTiles(uplink_.TakeDue(now_s, all), now_s);
}

// Collected for half a second: one message, not one per scan, while a vehicle passes a
// handful of candidates; so are the candidates it saw held.
void AgentNode::SendCandidates(double now_s) {
  constexpr double kPeriodS = 0.5;
  if (now_s < next_candidates_s_) return;
  next_candidates_s_ = now_s + kPeriodS;
  const CandidatesSeenFree seen = pipeline_.TakeSeenFree();
  sender_.SendCandidates(seen, pipeline_.TakeHeld(), maps_.version_in_use(), now_s);
}

void AgentNode::SendStatus(double now_s) {
  sender_.SendStatus(map_version(), state(), AllCounters(), verifier_.enabled(), now_s);
}

std::string AgentNode::state() const {
  if (!maps_.in_use()) return "waiting_for_map";
  if (!pose_.initialized()) return "waiting_for_pose";
  return building_ ? "building" : "running";
}

NamedCounters AgentNode::AllCounters() const {
  const TempMapOutbox& outbox = uplink_.outbox();
  NamedCounters out =
      CollectCounters(counters_, intake_.queue(), outbox.counters(), maps_.follower().counters(),
                      pipeline_.localizer().counters());
  out.emplace_back("tempmaps_pending", static_cast<int64_t>(outbox.pending()));
  out.emplace_back("tempmaps_retained", static_cast<int64_t>(outbox.retained().size()));
  out.emplace_back("retained_bytes", outbox.retained().bytes());
  out.emplace_back("tiles_queued", static_cast<int64_t>(uplink_.tiles_queued()));
  out.insert(out.end(), input_counters_.begin(), input_counters_.end());
  out.insert(out.end(), process_counters_.begin(), process_counters_.end());
  for (const auto& named : auth::Named(verifier_.counters())) out.push_back(named);
  return out;
}

}  // namespace fleetmap::vehicle_agent::node
