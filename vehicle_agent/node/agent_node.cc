#include "vehicle_agent/node/agent_node.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "fleetmap/candidates_free_t.hpp"
#include "fleetmap/map_candidates_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/status_counter.h"
#include "lcmtypes/transport_convert.h"
#include "vehicle_agent/node/agent_messages.h"

namespace fleetmap::vehicle_agent::node {
namespace {

const std::string kAggregatorStatus = lcmtypes::StatusChannel("aggregator");

// The covariance of an external pose, or the localizer's sigmas when it has none.
Eigen::Matrix3d ExternalCovariance(const core::PoseEstimate& pose, const LocalizerOptions& o) {
  const Eigen::Vector3d d = pose.covariance.diagonal();
  if (pose.covariance.allFinite() && d.minCoeff() > 0.0) return pose.covariance;
  return Eigen::Vector3d(o.external_sigma_xy_m * o.external_sigma_xy_m,
                         o.external_sigma_xy_m * o.external_sigma_xy_m,
                         o.external_sigma_theta_rad * o.external_sigma_theta_rad)
      .asDiagonal();
}

// Temporary-map numbers reserved on disk at a time: one fsync per 32 maps (every minute or
// two at one map per 3 s).
constexpr int32_t kSequenceBlock = 32;

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
  node->sequences_reserved_ = stored.next;
  node->ReserveSequences(stored.next);  // the first block now, not on the scan loop
  if (!stored.issue.ok()) {
    node->log_.Warning("temporary-map numbering: " + stored.issue.ToString() + "; going on from " +
                       std::to_string(stored.next));
  }
  if (static_map) {
    FLEETMAP_RETURN_IF_ERROR(node->follower_.Seed(std::move(*static_map), 0).WithContext("--map"));
    node->map_dirty_ = true;
  }
  if (node->options_.last_pose.period_s > 0 &&
      node->options_.initial_pose != InitialPoseSource::kFirstExternal) {
    core::Result<KeptPose> kept = node->poses_.Load();
    if (kept.ok()) {
      node->kept_pose_ = *kept;
    } else if (kept.status().code() != core::StatusCode::kNotFound) {
      node->log_.Warning("last pose not used: " + kept.status().ToString());
    }
  }
  const int reloaded = node->outbox_.LoadPersisted(now_s);
  if (reloaded > 0) {
    node->log_.Info(std::to_string(reloaded) + " unacknowledged temporary map(s) reloaded from " +
                    node->options_.outbox.state_dir + ": sending them again");
  }
  return node;
}

AgentNode::AgentNode(AgentNodeOptions options, Publisher* publisher, LogSink log, double now_s)
    : options_(std::move(options)),
      publisher_(publisher),
      log_(std::move(log)),
      sequences_(options_.outbox.state_dir),
      poses_(options_.outbox.state_dir),
      pipeline_(options_.pipeline),
      outbox_(options_.outbox),
      follower_(options_.map),
      queue_(options_.queue),
      sends_(options_.uplink_pacer),
      next_status_s_(now_s),
      // Sequence numbers follow the wall clock across restarts (auth/signer.h).
      signer_(options_.fleet_key, options_.pipeline.vehicle_id,
              auth::FirstSequence(
                  std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                      .count())),
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
      OnScan(data, size);
    } else if (channel == lcmtypes::OdomChannel(id) && options_.odometry_from_lcm) {
      ++counters_.messages;
      OnOdometry(data, size);
    } else if (channel == lcmtypes::ExternalPoseChannel(id) && options_.use_external_pose) {
      ++counters_.messages;
      OnExternalPose(data, size);
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

void AgentNode::Malformed(const std::string& channel, const core::Status& why) {
  ++counters_.malformed_messages;
  log_.Once(channel + ": " + core::StatusCodeName(why.code()),
            channel + ": bad message dropped: " + why.ToString());
}

template <typename T>
std::optional<T> AgentNode::Decode(const std::string& channel, const void* data, int size) {
  core::Result<T> m = lcmtypes::Decode<T>(data, size);
  if (!m.ok()) {
    Malformed(channel, m.status());
    return std::nullopt;
  }
  return std::move(m).value();
}

bool AgentNode::OurVehicle(const std::string& channel, const std::string& vehicle_id) {
  if (vehicle_id == options_.pipeline.vehicle_id) return true;
  ++counters_.wrong_vehicle;
  log_.Once(channel + ": wrong vehicle",
            channel + ": message names vehicle '" + vehicle_id.substr(0, 64) + "': dropped");
  return false;
}

void AgentNode::OnScan(const void* data, int size) {
  const std::string channel = lcmtypes::ScanChannel(options_.pipeline.vehicle_id);
  auto m = Decode<fleetmap::laser_scan_t>(channel, data, size);
  if (!m || !OurVehicle(channel, m->vehicle_id)) return;
  core::Result<core::LaserScan> scan = lcmtypes::FromMessage(*m);
  if (!scan.ok()) return Malformed(channel, scan.status());
  queue_.Push(std::move(scan).value());
}

void AgentNode::OnOdometry(const void* data, int size) {
  const std::string channel = lcmtypes::OdomChannel(options_.pipeline.vehicle_id);
  auto m = Decode<fleetmap::odometry_t>(channel, data, size);
  if (!m || !OurVehicle(channel, m->vehicle_id)) return;
  core::Result<core::OdometrySample> odom = lcmtypes::FromMessage(*m);
  if (!odom.ok()) return Malformed(channel, odom.status());
  queue_.Push(*odom);
}

void AgentNode::OnExternalPose(const void* data, int size) {
  const std::string channel = lcmtypes::ExternalPoseChannel(options_.pipeline.vehicle_id);
  auto m = Decode<fleetmap::pose_with_covariance_t>(channel, data, size);
  if (!m || !OurVehicle(channel, m->vehicle_id)) return;
  core::Result<core::PoseEstimate> pose = lcmtypes::FromMessage(*m);
  if (!pose.ok()) return Malformed(channel, pose.status());
  queue_.Push(ExternalPoseInput{*pose});
}

void AgentNode::OnDriverScan(const core::LaserScan& scan) {
  const core::Status valid = scan.Validate();
  if (!valid.ok()) return Malformed("scanner", valid);
  queue_.Push(scan);
}

void AgentNode::OnDriverOdometry(const core::OdometrySample& odom) {
  const core::Status valid = odom.Validate();
  if (!valid.ok()) return Malformed("odometry", valid);
  queue_.Push(odom);
}

void AgentNode::OnAck(const void* data, int size) {
  auto m = Decode<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel, data, size);
  if (!m || m->vehicle_id != options_.pipeline.vehicle_id) return;  // others' acks: not ours
  if (m->outcome < fleetmap::tempmap_ack_t::PENDING ||
      m->outcome > fleetmap::tempmap_ack_t::DUPLICATE)
    return Malformed(lcmtypes::kTempMapAckChannel, core::InvalidArgument("unknown ack outcome"));
  std::vector<int32_t> received;
  for (int16_t i : m->received_tiles) {
    if (i < 0 || i >= m->tile_count)
      return Malformed(lcmtypes::kTempMapAckChannel,
                       core::OutOfRange("acknowledged tile index outside the map's tiles"));
    received.push_back(i);
  }
  ++counters_.acks;
  const auto outcome = static_cast<AckOutcome>(m->outcome);
  const size_t pending_before = outbox_.pending();
  outbox_.OnAck(m->tempmap_seq, received, outcome, m->map_version);
  const bool finished = outbox_.pending() < pending_before;
  // Tiles still waiting for the pacer that the aggregator has, or no longer needs, stay here.
  const std::set<int32_t> have(received.begin(), received.end());
  sends_.Drop(m->tempmap_seq, [&](int32_t index) { return finished || have.count(index) > 0; });
  if (!finished) return;  // PENDING, a repeated final ack, or a map not pending
  const std::string what = "temporary map " + std::to_string(m->tempmap_seq);
  switch (outcome) {
    case AckOutcome::kMerged:
      ++counters_.maps_merged;
      log_.Info(what + " merged: map version " + std::to_string(m->map_version));
      break;
    case AckOutcome::kRejected:
      ++counters_.maps_rejected;
      log_.Info(what + " rejected by the aggregator: " + m->reason.substr(0, 200));
      break;
    case AckOutcome::kDuplicate:
      ++counters_.maps_duplicate;
      log_.Info(what + " was already handled by the aggregator (duplicate)");
      break;
    case AckOutcome::kPending:
      break;
  }
}

void AgentNode::MapTile(const std::string& channel, const core::Result<bool>& added) {
  if (!added.ok()) {
    log_.Once(channel + ": " + core::StatusCodeName(added.status().code()),
              channel + ": tile refused: " + added.status().ToString());
    return;
  }
  map_dirty_ |= *added;
}

void AgentNode::OnDelta(const void* data, int size) {
  auto m = Decode<fleetmap::map_delta_t>(lcmtypes::kMapDeltaChannel, data, size);
  if (!m) return;
  core::Result<core::DeltaTile> tile = lcmtypes::FromMessage(*m);
  if (!tile.ok()) return Malformed(lcmtypes::kMapDeltaChannel, tile.status());
  MapTile(lcmtypes::kMapDeltaChannel, follower_.OnDeltaTile(*tile));
}

void AgentNode::OnKeyframe(const void* data, int size) {
  auto m = Decode<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel, data, size);
  if (!m) return;
  core::Result<core::KeyframeTile> tile = lcmtypes::FromMessage(*m);
  if (!tile.ok()) return Malformed(lcmtypes::kMapKeyframeChannel, tile.status());
  MapTile(lcmtypes::kMapKeyframeChannel, follower_.OnKeyframeTile(*tile));
}

void AgentNode::OnAggregatorStatus(const void* data, int size, double now_s) {
  auto m = Decode<fleetmap::status_t>(kAggregatorStatus, data, size);
  if (!m) return;
  if (m->map_version >= 0) follower_.OnRemoteVersion(m->map_version, now_s);
  // An aggregator that recovered its state folder names the recovery and the version it
  // kept: the merged maps this vehicle still holds from after it are sent again, once.
  const int64_t recovery_id = lcmtypes::StatusCounter(*m, lcmtypes::kRecoveryIdCounter).value_or(0);
  const int64_t recovered_version =
      lcmtypes::StatusCounter(*m, lcmtypes::kRecoveredVersionCounter).value_or(-1);
  if (recovery_id == 0 || recovered_version < 0 || recovery_id == answered_recovery_) return;
  answered_recovery_ = recovery_id;
  const int resent = outbox_.ResendMergedAfter(recovered_version, now_s);
  log_.Info("the aggregator recovered its map at version " + std::to_string(recovered_version) +
            ": " + std::to_string(resent) + " merged temporary map(s) held here sent again");
}

void AgentNode::OnCandidates(const void* data, int size) {
  auto m = Decode<fleetmap::map_candidates_t>(lcmtypes::kMapCandidatesChannel, data, size);
  if (!m) return;
  auto set = candidates_.Add(*m);
  if (!set.ok()) return Malformed(lcmtypes::kMapCandidatesChannel, set.status());
  if (*set) pipeline_.SetCandidates(**set);
}

// ---- processing -----------------------------------------------------------------------------

void AgentNode::Tick(double now_s) {
  if (map_dirty_) ApplyMap();
  for (const SensorInput& input : queue_.TakeAll()) Process(input, now_s);
  SendMapRequest(now_s);
  SendTiles(now_s);
  SendSeenFree(now_s);
  if (now_s >= next_status_s_) {
    SendStatus(now_s);
    // Not now_s + period: a late tick must not shift every later heartbeat.
    next_status_s_ = std::max(next_status_s_ + options_.status_period_s, now_s);
  }
}

void AgentNode::ApplyMap() {
  map_dirty_ = false;
  // Dirty means a tile completed a version (or the static map came in): after an aggregator
  // restart a new map may carry a version number we held before.
  if (!follower_.has_map()) return;
  const core::Status s = pipeline_.SetMap(follower_.map(), follower_.version());
  if (!s.ok()) {
    ++counters_.map_swaps_failed;
    log_.Once("map swap",
              "map version " + std::to_string(follower_.version()) + " not used: " + s.ToString());
    return;
  }
  const bool first = !map_applied_;
  map_applied_ = true;
  applied_version_ = follower_.version();
  log_.Info("map version " + std::to_string(applied_version_) + " in use");
  if (!first) return;
  // The first map initialises the filter (given pose or global), unless an external pose
  // is to do it.
  // A kept pose waits for the first odometry sample, which tells whether it still holds.
  pose_initialized_ = options_.initial_pose != InitialPoseSource::kFirstExternal && !kept_pose_;
  if (early_external_) InitializeFromExternal(*early_external_);
}

void AgentNode::Process(const SensorInput& input, double now_s) {
  if (const auto* scan = std::get_if<core::LaserScan>(&input)) return ProcessScan(*scan, now_s);
  if (const auto* odom = std::get_if<core::OdometrySample>(&input)) {
    ++counters_.odometry;
    pipeline_.AddOdometry(*odom);
    if (!odom->Validate().ok()) return;
    odometry_ = odom->pose_in_odom;
    if (kept_pose_) ResumeFromKeptPose(odom->pose_in_odom);
    return;
  }
  ProcessExternalPose(std::get<ExternalPoseInput>(input).pose);
}

void AgentNode::ProcessExternalPose(const core::PoseEstimate& pose) {
  ++counters_.external_poses;
  if (!map_applied_) {
    early_external_ = pose;
    return;
  }
  if (!pose_initialized_) return InitializeFromExternal(pose);
  (void)pipeline_.AddExternalPose(pose);  // the localizer counts what it refuses
}

void AgentNode::InitializeFromExternal(const core::PoseEstimate& pose) {
  early_external_.reset();
  if (options_.initial_pose != InitialPoseSource::kFirstExternal || pose_initialized_) return;
  const core::Status s = pipeline_.InitializeAt(
      pose.pose_in_map, ExternalCovariance(pose, options_.pipeline.localizer));
  if (!s.ok()) return Malformed(lcmtypes::ExternalPoseChannel(options_.pipeline.vehicle_id), s);
  pose_initialized_ = true;
  log_.Info("initial pose from the external localization");
}

void AgentNode::ProcessScan(const core::LaserScan& scan, double now_s) {
  if (!map_applied_) {
    ++counters_.scans_waiting_for_map;
    return;
  }
  if (!pose_initialized_) {
    ++counters_.scans_waiting_for_pose;
    return;
  }
  const AgentStep step = pipeline_.AddScan(scan);
  ++counters_.scans;
  building_ = step.building;
  ReportLocalization(step.localization);
  KeepPose(step, now_s, /*now=*/false);
  last_step_ = step;
  PublishStep(scan, step);
  if (step.closed_map) Keep(*step.closed_map, now_s);
}

void AgentNode::ResumeFromKeptPose(const core::Pose2& odometry) {
  const KeptPose kept = *kept_pose_;
  kept_pose_.reset();
  if (map_applied_) pose_initialized_ = true;
  if (!StillThere(kept, odometry, options_.last_pose)) {
    const core::Pose2 moved = core::Between(kept.odometry, odometry);
    char text[160];
    std::snprintf(text, sizeof(text),
                  "last pose not used: the odometry moved %.2f m, %.3f rad since it was kept; ",
                  std::hypot(moved.x_m, moved.y_m), moved.theta_rad);
    log_.Info(text + std::string(options_.initial_pose == InitialPoseSource::kGlobal
                                     ? "searching the whole map"
                                     : "starting from the given pose"));
    return;
  }
  const LocalizerOptions& l = options_.pipeline.localizer;
  const Eigen::Matrix3d around =
      Eigen::Vector3d(l.global_sigma_xy_m, l.global_sigma_xy_m, l.global_sigma_theta_rad)
          .cwiseAbs2()
          .asDiagonal();
  const core::Status s = pipeline_.InitializeAt(kept.base_in_map, around);
  if (!s.ok()) {
    log_.Warning("last pose not used: " + s.ToString());
    return;
  }
  ++counters_.starts_from_last_pose;
  log_.Info("starting from the last pose kept in " + poses_.path() +
            ": the vehicle has not moved since");
}

void AgentNode::KeepPose(const AgentStep& step, double now_s, bool now) {
  if (!poses_.enabled() || !(options_.last_pose.period_s > 0) || !odometry_) return;
  if (!now && now_s < next_keep_s_) return;
  if (!step.well_localized) return;  // only a pose worth starting from
  if (last_kept_ && StillThere(*last_kept_, *odometry_, options_.last_pose)) return;
  const KeptPose kept{step.pose.pose_in_map, *odometry_, step.pose.map_version};
  next_keep_s_ = now_s + options_.last_pose.period_s;
  const core::Status stored = poses_.Store(kept);
  if (!stored.ok()) {
    log_.Once("last pose", "cannot keep the last pose: " + stored.ToString());
    return;
  }
  last_kept_ = kept;
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

void AgentNode::Keep(const core::TempMap& map, double now_s) {
  ++counters_.tempmaps_closed;
  // The number goes on disk before the map leaves: a crash now cannot reuse it.
  if (map.sequence >= sequences_reserved_) ReserveSequences(map.sequence);
  const core::Status added = outbox_.Add(map, now_s);
  if (!added.ok()) {
    log_.Once("outbox", "temporary map not kept: " + added.ToString());
    return;
  }
  log_.Info("temporary map " + std::to_string(map.sequence) +
            " closed: " + std::to_string(map.grid.geometry().width()) + " x " +
            std::to_string(map.grid.geometry().height()) + " cells over " +
            std::to_string(static_cast<int>(std::lround(map.end_s - map.start_s))) + " s");
}

// Numbers are reserved a block at a time, so that the fsync (which can stall the scan loop for
// seconds on a busy disk) comes once per block, not once per map; a restart skips the rest of
// a block, and the aggregator needs numbers that are unique, not consecutive.
void AgentNode::ReserveSequences(int32_t from) {
  const int32_t reserve = from < std::numeric_limits<int32_t>::max() - kSequenceBlock
                              ? from + kSequenceBlock
                              : std::numeric_limits<int32_t>::max();
  const core::Status stored = sequences_.Store(reserve);
  if (stored.ok()) {
    sequences_reserved_ = reserve;
  } else {
    log_.Once("sequence store", "cannot store the numbering: " + stored.ToString());
  }
}

void AgentNode::Shutdown(double now_s) {
  if (map_dirty_) ApplyMap();
  for (const SensorInput& input : queue_.TakeAll()) Process(input, now_s);
  if (std::optional<core::TempMap> last = pipeline_.Flush(now_s)) Keep(*last, now_s);
  if (last_step_) KeepPose(*last_step_, now_s, /*now=*/true);
  building_ = false;
  SendTiles(now_s, /*all=*/true);  // at exit: what is queued goes now (it is on disk too)
  SendStatus(now_s);
}

void AgentNode::Drain(double now_s) {
  if (map_dirty_) ApplyMap();
  SendTiles(now_s, /*all=*/true);
}

// ---- output ---------------------------------------------------------------------------------

int64_t AgentNode::Utime(double now_s) const {
  return lcmtypes::ToUtime(now_s + options_.utime_offset_s);
}

template <typename T>
void AgentNode::Send(Link link, const std::string& channel, const T& message) {
  std::vector<uint8_t> bytes = Encode(message);
  signer_.Seal(channel, bytes);
  if (!publisher_->Publish(link, channel, bytes)) {
    ++counters_.publish_failures;
    log_.Once("publish " + channel, "cannot publish on " + channel + " (" + LinkName(link) + ")");
  }
}

void AgentNode::PublishStep(const core::LaserScan& scan, const AgentStep& step) {
  const std::string& id = options_.pipeline.vehicle_id;
  Send(options_.pose_link, lcmtypes::PoseChannel(id), lcmtypes::ToMessage(step.pose, id));
  // The map being built, or the last one: sequences are handed out one per started map.
  const auto sequence = static_cast<int32_t>(options_.pipeline.first_sequence - 1 +
                                             pipeline_.counters().temp_maps_started);
  Send(options_.pose_link, lcmtypes::DivergenceChannel(id),
       DivergenceMessage(id, scan.stamp_s, step, sequence));
}

void AgentNode::SendTiles(double now_s, bool all) {
  sends_.Add(outbox_.Due(now_s));
  const std::string channel = lcmtypes::TempMapChannel(options_.pipeline.vehicle_id);
  for (const core::TempMapTile& tile : sends_.Take(now_s, all))
    Send(Link::kUplink, channel, lcmtypes::ToMessage(tile, Utime(now_s)));
}

// Collected for half a second: one message, not one per scan, while a vehicle passes a
// handful of candidates; so are the candidates it saw held.
void AgentNode::SendSeenFree(double now_s) {
  constexpr double kSeenFreePeriodS = 0.5;
  if (now_s < next_seen_free_s_) return;
  next_seen_free_s_ = now_s + kSeenFreePeriodS;
  const CandidatesSeenFree seen = pipeline_.TakeSeenFree();
  fleetmap::candidates_free_t m;
  m.utime = Utime(now_s);
  m.vehicle_id = options_.pipeline.vehicle_id;
  m.map_version = applied_version_;
  m.first_pass_utime = lcmtypes::ToUtime(seen.first_pass_s);  // scan time, as maps carry it
  m.last_pass_utime = lcmtypes::ToUtime(seen.last_pass_s);
  const std::string channel = lcmtypes::CandidatesFreeChannel(options_.pipeline.vehicle_id);
  for (size_t begin = 0; begin < seen.cells.size();
       begin += lcmtypes::kMaxCandidateCellsPerMessage) {
    const size_t end =
        std::min(seen.cells.size(), begin + size_t{lcmtypes::kMaxCandidateCellsPerMessage});
    m.cells.assign(seen.cells.begin() + static_cast<std::ptrdiff_t>(begin),
                   seen.cells.begin() + static_cast<std::ptrdiff_t>(end));
    m.num_cells = static_cast<int32_t>(m.cells.size());
    Send(Link::kUplink, channel, m);
    ++counters_.seen_free_reports;
  }
  const std::string held_channel = lcmtypes::CandidatesHeldChannel(options_.pipeline.vehicle_id);
  for (const auto& held : HeldMessages(options_.pipeline.vehicle_id, applied_version_,
                                       pipeline_.TakeHeld(), Utime(now_s))) {
    Send(Link::kUplink, held_channel, held);
    ++counters_.held_reports;
  }
}

void AgentNode::SendMapRequest(double now_s) {
  const int64_t resets = follower_.counters().resets;
  const std::optional<int32_t> have = follower_.RequestDue(now_s);
  if (follower_.counters().resets != resets) {
    log_.Warning(
        "the aggregator's map versions went back below " + std::to_string(applied_version_) +
        " (restarted without its state?): asking for its map, localizing on ours meanwhile");
  }
  if (have) {
    Send(Link::kUplink, lcmtypes::kMapRequestChannel,
         MapRequestMessage(options_.pipeline.vehicle_id, *have, Utime(now_s)));
  }
}

void AgentNode::SendStatus(double now_s) {
  const std::string process = "agent_" + options_.pipeline.vehicle_id;
  fleetmap::status_t status = StatusMessage(process, options_.software_version, map_version(),
                                            state(), AllCounters(), Utime(now_s));
  status.authenticated = verifier_.enabled();
  Send(Link::kUplink, lcmtypes::StatusChannel(process), status);
}

std::string AgentNode::state() const {
  if (!map_applied_) return "waiting_for_map";
  if (!pose_initialized_) return "waiting_for_pose";
  return building_ ? "building" : "running";
}

NamedCounters AgentNode::AllCounters() const {
  NamedCounters out = CollectCounters(counters_, queue_, outbox_.counters(), follower_.counters(),
                                      pipeline_.localizer().counters());
  out.emplace_back("tempmaps_pending", static_cast<int64_t>(outbox_.pending()));
  out.emplace_back("tempmaps_retained", static_cast<int64_t>(outbox_.retained().size()));
  out.emplace_back("retained_bytes", outbox_.retained().bytes());
  out.emplace_back("tiles_queued", static_cast<int64_t>(sends_.size()));
  out.insert(out.end(), input_counters_.begin(), input_counters_.end());
  out.insert(out.end(), process_counters_.begin(), process_counters_.end());
  for (const auto& named : auth::Named(verifier_.counters())) out.push_back(named);
  return out;
}

}  // namespace fleetmap::vehicle_agent::node
