#include "aggregator/node/aggregator_node.h"

#include <algorithm>
#include <chrono>
#include <set>

#include "aggregator/node/candidate_messages.h"
#include "aggregator/node/map_hash.h"
#include "aggregator/node/messages.h"
#include "fleetmap/map_request_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::aggregator::node {
namespace {

constexpr size_t kMaxVehicleIdBytes = 64;

std::vector<int32_t> AllTiles(int32_t count) {
  std::vector<int32_t> all;
  for (int32_t i = 0; i < count; ++i) all.push_back(i);
  return all;
}

}  // namespace

core::Result<std::unique_ptr<AggregatorNode>> AggregatorNode::Create(Aggregator aggregator,
                                                                     AggregatorNodeOptions options,
                                                                     Publisher* publisher,
                                                                     LogSink log, double now_s) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  TileSpool spool;
  if (!options.spool_dir.empty())
    FLEETMAP_ASSIGN_OR_RETURN(spool, TileSpool::Open(options.spool_dir));
  std::unique_ptr<AggregatorNode> node(new AggregatorNode(std::move(aggregator), std::move(options),
                                                          publisher, std::move(log), now_s));
  node->spool_ = std::move(spool);
  node->RestoreSpool(now_s);
  return node;
}

AggregatorNode::AggregatorNode(Aggregator aggregator, AggregatorNodeOptions options,
                               Publisher* publisher, LogSink log, double now_s)
    : aggregator_(std::move(aggregator)),
      options_(std::move(options)),
      publisher_(publisher),
      log_(std::move(log)),
      assembler_(options_.assembler),
      handled_(options_.max_remembered_rejections),
      acks_(options_.pending_ack_interval_s),
      requests_(options_.keyframe_min_interval_s),
      next_status_s_(now_s),
      next_keyframe_s_(now_s + options_.keyframe_period_s),
      // Sequence numbers follow the wall clock across restarts, whatever time the node
      // is handed (auth/signer.h).
      signer_(options_.fleet_key, options_.process_name,
              auth::FirstSequence(
                  std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                      .count())),
      verifier_(options_.fleet_key),
      limits_(options_.limits),
      held_(options_.max_held_maps) {
  handled_.LoadMerged(aggregator_.store().provenance());
}

void AggregatorNode::RestoreSpool(double now_s) {
  int bad_files = 0;
  const std::vector<SpooledTile> tiles = spool_.LoadAll(&bad_files);
  counters_.spool_errors += bad_files;
  int restored = 0;
  std::set<MapKey> dropped;
  for (const SpooledTile& s : tiles) {
    if (dropped.count(s.key)) continue;
    auto msg = lcmtypes::Decode<fleetmap::tempmap_tile_t>(s.bytes.data(),
                                                          static_cast<int>(s.bytes.size()));
    auto tile =
        msg.ok() ? lcmtypes::FromMessage(*msg) : core::Result<core::TempMapTile>(msg.status());
    if (!tile.ok() || tile->vehicle_id != s.key.vehicle_id || tile->sequence != s.key.sequence ||
        tile->index != s.index) {
      // The vehicle will not send an acknowledged tile again: the map cannot complete.
      ++counters_.spool_errors;
      log_.Warning("tile spool: dropping " + s.key.ToString() +
                   ": a kept tile is unreadable, the map cannot be completed");
      dropped.insert(s.key);
      spool_.Remove(s.key);
      assembler_.Drop(s.key.vehicle_id, s.key.sequence);
      incoming_.erase(s.key);
      acks_.Forget(s.key);
      continue;
    }
    if (handled_.Find(s.key)) {  // merged just before the last run stopped
      spool_.Remove(s.key);
      continue;
    }
    AddTile(*msg, *tile, s.bytes, /*from_spool=*/true, now_s);
    ++restored;
  }
  if (restored > 0)
    log_.Info("restored " + std::to_string(restored) + " acknowledged tiles of incomplete maps");
}

void AggregatorNode::OnMessage(const std::string& channel, const void* data, int size,
                               double now_s) {
  ++counters_.messages;
  if (size < 0 || (size > 0 && data == nullptr)) {
    Refuse("no payload", counters_.malformed_messages, channel + ": a message without payload");
    return;
  }
  if (size > options_.limits.max_received_bytes) {
    Refuse("oversize received", counters_.oversize_received,
           channel.substr(0, 80) + ": a message of " + std::to_string(size) +
               " bytes refused (limits.max_received_bytes " +
               std::to_string(options_.limits.max_received_bytes) + ")");
    return;
  }
  const bool tile = lcmtypes::HasPrefix(channel, lcmtypes::kTempMapPrefix);
  if (channel == lcmtypes::kTempMapAckChannel) {
    ++counters_.ignored_messages;  // matches TEMPMAP_.*: our own, when both links share a group
    return;
  }
  const bool seen_free = lcmtypes::HasPrefix(channel, lcmtypes::kCandidatesFreePrefix);
  const bool held = lcmtypes::HasPrefix(channel, lcmtypes::kCandidatesHeldPrefix);
  if (!tile && !seen_free && !held && channel != lcmtypes::kMapRequestChannel) {
    Refuse(
        "unknown channel", counters_.unknown_channel,
        "message on channel '" + channel.substr(0, 80) + "', which the aggregator does not read");
    return;
  }
  // TEMPMAP_<id>, CANDIDATES_FREE_<id> and CANDIDATES_HELD_<id> belong to vehicle <id>; any
  // member of the fleet may ask for maps.
  const std::string owner =
      lcmtypes::ChannelOwner(channel, options_.process_name).value_or(std::string());
  auth::Opened opened;
  const auth::Verdict verdict = verifier_.Open(channel, data, size, owner, &opened);
  if (verdict != auth::Verdict::kAccepted) {
    Refuse(std::string("auth: ") + auth::VerdictName(verdict), counters_.auth_refused,
           channel.substr(0, 80) + ": " + auth::RefusalText(verdict));
    return;
  }
  if (tile) {
    OnTile(channel, opened.data, opened.size, now_s);
  } else if (seen_free) {
    OnSeenFree(channel, opened.data, opened.size, now_s);
  } else if (held) {
    OnHeld(channel, opened.data, opened.size, now_s);
  } else {
    OnRequest(opened.data, opened.size);
  }
}

bool AggregatorNode::Throttled(const std::string& vehicle, double now_s) {
  if (limits_.AllowTile(vehicle, now_s)) return false;
  ++counters_.throttled_tiles;
  if (limits_.FirstThrottle(vehicle)) {
    log_.Warning("vehicle '" + vehicle.substr(0, kMaxVehicleIdBytes) + "' sends more than " +
                 std::to_string(options_.limits.tiles_per_s) +
                 " tiles/s: throttled, its tiles over the rate are dropped (other vehicles are "
                 "not affected; counted in throttled_tiles)");
  }
  return true;
}

int AggregatorNode::PendingMaps(const std::string& vehicle) const {
  int n = 0;
  for (const auto& [key, in] : incoming_) n += key.vehicle_id == vehicle;
  return n;
}

void AggregatorNode::Refuse(const std::string& cause, int64_t& counter, const std::string& line) {
  ++counter;
  log_.Once(cause, line);
}

void AggregatorNode::OnTile(const std::string& channel, const void* data, int size, double now_s) {
  auto msg = lcmtypes::Decode<fleetmap::tempmap_tile_t>(data, size);
  if (!msg.ok()) {
    Refuse("TEMPMAP: malformed", counters_.malformed_messages,
           channel + ": not a tempmap_tile_t: " + msg.status().ToString());
    return;
  }
  const std::string suffix = lcmtypes::ChannelSuffix(channel, lcmtypes::kTempMapPrefix);
  if (msg->vehicle_id != suffix) {
    Refuse("TEMPMAP: wrong vehicle id", counters_.wrong_vehicle_id,
           channel + ": a tile of vehicle '" + msg->vehicle_id.substr(0, kMaxVehicleIdBytes) +
               "' refused: a vehicle sends only its own maps, on its own channel");
    return;
  }
  auto tile = lcmtypes::FromMessage(*msg);
  if (!tile.ok()) {
    Refuse("TEMPMAP: invalid tile", counters_.invalid_tiles,
           channel + ": invalid tile: " + tile.status().ToString());
    return;
  }
  // Counted once the tile is authentic and valid: forged or broken tiles on a vehicle's
  // channel must not use up its rate.
  if (Throttled(suffix, now_s)) return;
  const auto* bytes = static_cast<const uint8_t*>(data);
  AddTile(*msg, *tile, std::vector<uint8_t>(bytes, bytes + size), /*from_spool=*/false, now_s);
}

void AggregatorNode::AddTile(const fleetmap::tempmap_tile_t& msg, const core::TempMapTile& tile,
                             const std::vector<uint8_t>& bytes, bool from_spool, double now_s) {
  const MapKey key{tile.vehicle_id, tile.sequence};
  ++counters_.tiles_received;
  const double map_s = lcmtypes::FromUtime(msg.utime);
  if (auto handled = handled_.Find(key)) {
    ++counters_.duplicates;
    if (acks_.FinalAckDue(key, now_s)) {
      SendFinal(key, tile.count, fleetmap::tempmap_ack_t::DUPLICATE, "", handled->version, now_s);
    }
    return;
  }
  if (held_.Contains(key)) {  // a resend of a map waiting for its turn
    ++counters_.duplicates;
    return;
  }
  if (Unpersisted(key)) {  // a resend of a map waiting for the journal: try the disk now
    ++counters_.duplicates;
    RetryUnpersisted(now_s);
    return;
  }
  if (auto retry = retry_.find(key); retry != retry_.end()) {
    // A map over the merge rate found no room to be held and waited for this resend.
    const Retry again = retry->second;
    retry_.erase(retry);
    Complete(key, again.map, again.tile_count, map_s, now_s);
    return;
  }
  if (!incoming_.count(key) &&
      PendingMaps(key.vehicle_id) >= options_.limits.max_pending_maps_per_vehicle) {
    Refuse("TEMPMAP: vehicle's maps full", counters_.vehicle_maps_full,
           "vehicle '" + key.vehicle_id + "' has " +
               std::to_string(options_.limits.max_pending_maps_per_vehicle) +
               " incomplete temporary maps; " + key.ToString() + " has to wait for its resend");
    return;
  }
  if (!incoming_.count(key) &&
      static_cast<int>(incoming_.size()) >= options_.assembler.max_pending_maps) {
    Refuse("TEMPMAP: too many maps", counters_.assembler_full,
           "too many temporary maps being received at once (" +
               std::to_string(options_.assembler.max_pending_maps) + "); " + key.ToString() +
               " has to wait for the vehicle's resend");
    return;
  }
  const std::vector<int32_t> before = assembler_.Received(key.vehicle_id, key.sequence);
  const bool repeated = std::binary_search(before.begin(), before.end(), tile.index);
  auto added = assembler_.Add(tile);
  if (!added.ok()) {
    Refuse("TEMPMAP: inconsistent tile", counters_.inconsistent_tiles,
           "tile " + std::to_string(tile.index) + " of " + key.ToString() +
               " refused: " + added.status().ToString());
    return;
  }
  if (repeated) ++counters_.tiles_repeated;
  if (!added->has_value()) {
    Incoming& in = incoming_[key];
    in.tile_count = tile.count;
    if (from_spool) {
      acks_.Restore(key, now_s);
    } else {
      if (!repeated && spool_.enabled()) in.unspooled[tile.index] = bytes;
      if (acks_.OnTile(key, repeated, now_s)) SendPending(key, now_s);
    }
    return;
  }
  incoming_.erase(key);
  acks_.Forget(key);
  ++counters_.maps_completed;
  Complete(key, **added, tile.count, map_s, now_s);
}

void AggregatorNode::Complete(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                              double map_s, double now_s) {
  if (!unpersisted_.empty()) {  // behind the maps waiting for the journal, in arrival order
    KeepUnpersisted({key, map, tile_count, map_s}, now_s);
    return;
  }
  if (!held_.Waiting(key.vehicle_id) && limits_.AllowMerge(key.vehicle_id, map_s, now_s)) {
    Merge(key, map, tile_count, map_s, now_s);
    return;
  }
  const std::string over_rate = "vehicle '" + key.vehicle_id + "' completes more than " +
                                std::to_string(options_.limits.merges_per_min) + " maps per minute";
  if (held_.Hold({key, map, tile_count, map_s})) {
    Refuse("TEMPMAP: merge rate", counters_.throttled_merges,
           over_rate + ": " + key.ToString() +
               " and its next maps are held, merged in order as the rate allows");
    return;
  }
  Refuse("TEMPMAP: held maps full", counters_.throttled_merges,
         over_rate + " and " + std::to_string(options_.max_held_maps) +
             " maps are held: " + key.ToString() + " waits unacknowledged for a resend");
  if (static_cast<int>(retry_.size()) < options_.max_retry_maps) retry_[key] = {map, tile_count};
}

void AggregatorNode::ReleaseHeld(double now_s) {
  const auto allow = [&](const std::string& vehicle, double map_s) {
    return limits_.AllowMerge(vehicle, map_s, now_s);
  };
  for (const HeldMap& m : held_.Release(allow)) Merge(m.key, m.map, m.tile_count, m.map_s, now_s);
}

void AggregatorNode::Merge(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                           double map_s, double now_s) {
  if (TryMerge(key, map, tile_count, map_s, now_s)) return;
  limits_.RefundMerge(key.vehicle_id);  // a merge the disk refused costs the vehicle nothing
  KeepUnpersisted({key, map, tile_count, map_s}, now_s);
}

bool AggregatorNode::Unpersisted(const MapKey& key) const {
  return std::any_of(unpersisted_.begin(), unpersisted_.end(),
                     [&](const HeldMap& m) { return m.key == key; });
}

void AggregatorNode::KeepUnpersisted(HeldMap map, double now_s) {
  if (unpersisted_.empty()) next_persist_try_s_ = now_s + kPersistRetryS;
  if (static_cast<int>(unpersisted_.size()) < options_.max_retry_maps) {
    unpersisted_.push_back(std::move(map));
    return;
  }
  Refuse("TEMPMAP: journal backlog full", counters_.persist_backlog_full,
         std::to_string(options_.max_retry_maps) + " maps wait for the journal: " +
             map.key.ToString() + " waits unacknowledged for the vehicle's resend");
}

void AggregatorNode::RetryUnpersisted(double now_s) {
  while (!unpersisted_.empty()) {
    const HeldMap& m = unpersisted_.front();
    if (!TryMerge(m.key, m.map, m.tile_count, m.map_s, now_s)) {
      next_persist_try_s_ = now_s + kPersistRetryS;
      return;
    }
    unpersisted_.pop_front();
  }
}

bool AggregatorNode::TryMerge(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                              double map_s, double now_s) {
  auto report = aggregator_.Submit(map, map_s);
  if (!report.ok() && report.status().code() == core::StatusCode::kIoError) {
    ++counters_.persist_errors;
    if (!persist_failed_) {
      log_.Warning("merge of " + key.ToString() +
                   " not journaled, not acknowledged: " + report.status().ToString() +
                   "; it and the maps after it are kept and merged in order once the journal "
                   "writes again (tried every " +
                   std::to_string(kPersistRetryS) + " s and at each resend)");
    }
    persist_failed_ = true;
    return false;
  }
  spool_.Remove(key);
  if (!report.ok()) {  // the store refused the commit: a bug, not the vehicle's fault
    ++counters_.submit_errors;
    log_.Warning("merge of " + key.ToString() + " failed: " + report.status().ToString());
    handled_.Rejected(key, aggregator_.store().version());
    ++counters_.maps_rejected;
    SendFinal(key, tile_count, fleetmap::tempmap_ack_t::REJECTED,
              "internal error: " + report.status().ToString(), aggregator_.store().version(),
              now_s);
    return true;
  }
  if (report->accepted) persist_failed_ = false;
  if (!report->warning.empty()) {
    ++counters_.snapshot_errors;
    log_.Warning(report->warning);
  }
  if (report->accepted) {
    ++counters_.maps_merged;
    handled_.Merged(key, report->version);
    SendFinal(key, tile_count, fleetmap::tempmap_ack_t::MERGED, "", report->version, now_s);
  } else {
    ++counters_.maps_rejected;
    handled_.Rejected(key, report->version);
    SendFinal(key, tile_count, fleetmap::tempmap_ack_t::REJECTED, report->reason_text,
              report->version, now_s);
  }
  Send(Link::kDownlink, lcmtypes::kMergeReportChannel,
       ReportMessage(*report, map.anchor_in_map, options_.max_report_matches,
                     lcmtypes::ToUtime(map_s)));
  if (publisher_) ++counters_.merge_reports_sent;
  if (report->accepted) {
    SendDelta(report->delta, now_s);
    SendCandidates(now_s);
  }
  return true;
}

template <typename Message>
std::optional<Message> AggregatorNode::VehicleReport(const std::string& channel, const void* data,
                                                     int size, const char* prefix,
                                                     const std::string& name) {
  auto msg = lcmtypes::Decode<Message>(data, size);
  if (!msg.ok()) {
    Refuse(name + ": malformed", counters_.malformed_messages,
           channel + ": not a " + Message::getTypeName() + ": " + msg.status().ToString());
    return std::nullopt;
  }
  if (msg->vehicle_id != lcmtypes::ChannelSuffix(channel, prefix)) {
    Refuse(name + ": wrong vehicle id", counters_.wrong_vehicle_id,
           channel + ": a report of vehicle '" + msg->vehicle_id.substr(0, kMaxVehicleIdBytes) +
               "' refused: a vehicle reports on its own channel");
    return std::nullopt;
  }
  return std::move(*msg);
}

void AggregatorNode::OnSeenFree(const std::string& channel, const void* data, int size,
                                double now_s) {
  const auto msg = VehicleReport<fleetmap::candidates_free_t>(
      channel, data, size, lcmtypes::kCandidatesFreePrefix, "CANDIDATES_FREE");
  if (!msg) return;
  auto report = SeenFreeFromMessage(*msg, aggregator_.store().current_map().geometry().num_cells());
  if (!report.ok())
    return Refuse("CANDIDATES_FREE: invalid", counters_.bad_seen_free,
                  channel + ": report refused: " + report.status().ToString());
  ++counters_.seen_free_reports;
  ReportApplied(msg->vehicle_id,
                aggregator_.DropCandidatesSeenFree(msg->vehicle_id, *report, now_s),
                counters_.candidates_dropped, "saw free not dropped", now_s);
}

void AggregatorNode::OnHeld(const std::string& channel, const void* data, int size, double now_s) {
  const auto msg = VehicleReport<fleetmap::candidates_held_t>(
      channel, data, size, lcmtypes::kCandidatesHeldPrefix, "CANDIDATES_HELD");
  if (!msg) return;
  auto report = HeldFromMessage(*msg, aggregator_.store().current_map().geometry().num_cells());
  if (!report.ok())
    return Refuse("CANDIDATES_HELD: invalid", counters_.bad_held,
                  channel + ": report refused: " + report.status().ToString());
  ++counters_.held_reports;
  ReportApplied(msg->vehicle_id, aggregator_.ConfirmCandidatesHeld(msg->vehicle_id, *report, now_s),
                counters_.candidates_held_added, "saw held not added", now_s);
}

// The cells a vehicle's report changed, in a version of their own: counted, and their delta
// and the new set of candidates go out. A failed journal write changed nothing.
void AggregatorNode::ReportApplied(const std::string& vehicle,
                                   const core::Result<std::vector<int64_t>>& cells,
                                   int64_t& counter, const std::string& what, double now_s) {
  if (!cells.ok()) {
    ++counters_.persist_errors;
    log_.Warning("candidates " + vehicle.substr(0, kMaxVehicleIdBytes) + " " + what + ": " +
                 cells.status().ToString());
    return;
  }
  if (cells->empty()) return;
  counter += static_cast<int64_t>(cells->size());
  const CurrentMapStore& store = aggregator_.store();
  if (auto delta = store.Delta(store.version() - 1); delta.ok()) SendDelta(*delta, now_s);
  SendCandidates(now_s);
}

void AggregatorNode::OnRequest(const void* data, int size) {
  auto msg = lcmtypes::Decode<fleetmap::map_request_t>(data, size);
  if (!msg.ok()) {
    Refuse("MAP_REQUEST: malformed", counters_.malformed_messages,
           "MAP_REQUEST: not a map_request_t: " + msg.status().ToString());
    return;
  }
  const core::TileLayout layout(aggregator_.store().current_map().geometry(),
                                aggregator_.options().store.tiles.tile_size_cells);
  const bool tiles_ok = msg->num_tiles <= layout.num_tiles() &&
                        std::all_of(msg->tiles.begin(), msg->tiles.end(),
                                    [&](int32_t t) { return t >= 0 && t < layout.num_tiles(); });
  if (msg->vehicle_id.size() > kMaxVehicleIdBytes || msg->have_version < -1 || !tiles_ok) {
    Refuse("MAP_REQUEST: impossible", counters_.bad_requests,
           "MAP_REQUEST from '" + msg->vehicle_id.substr(0, kMaxVehicleIdBytes) +
               "' refused: have_version " + std::to_string(msg->have_version) + ", " +
               std::to_string(msg->num_tiles) + " tiles (the map has " +
               std::to_string(layout.num_tiles()) + ")");
    return;
  }
  ++counters_.requests;
  const CurrentMapStore& store = aggregator_.store();
  const int64_t have = msg->have_version;
  const int64_t current = static_cast<int64_t>(store.version());
  if (!msg->tiles.empty() || have < 0 || have > current) {
    requests_.AddKeyframe(msg->tiles);  // (a vehicle ahead of us: our state was lost)
  } else if (have < current) {
    const bool retained =
        store.Delta(static_cast<uint64_t>(have)).ok() && store.Delta(current - 1).ok();
    if (retained) {
      requests_.AddDeltas(static_cast<uint64_t>(have));
    } else {
      requests_.AddKeyframe({});
    }
  }  // have == current: the vehicle is up to date
}

void AggregatorNode::Tick(double now_s) {
  if (!unpersisted_.empty() && now_s >= next_persist_try_s_) RetryUnpersisted(now_s);
  // Held maps wait behind any map the journal refused, which keeps the arrival order.
  if (unpersisted_.empty()) ReleaseHeld(now_s);
  for (const MapKey& key : acks_.Due(now_s)) SendPending(key, now_s);
  DropStale(now_s);
  if (options_.keyframe_period_s > 0 && now_s >= next_keyframe_s_) {
    SendKeyframe(nullptr, now_s);
    SendCandidates(now_s);  // for vehicles that joined since they last changed
    requests_.WholeKeyframeSent(now_s);
    next_keyframe_s_ = now_s + options_.keyframe_period_s;
  }
  SendRequested(now_s);
  if (now_s >= next_status_s_) {
    SendStatus(now_s);
    next_status_s_ = now_s + options_.status_period_s;
  }
}

void AggregatorNode::DropStale(double now_s) {
  for (const MapKey& key : acks_.Stale(now_s, options_.pending_map_timeout_s)) {
    ++counters_.maps_evicted;
    log_.Info("dropping incomplete temporary map " + key.ToString() + ": no tile for " +
              std::to_string(options_.pending_map_timeout_s) + " s");
    assembler_.Drop(key.vehicle_id, key.sequence);
    spool_.Remove(key);
    incoming_.erase(key);
    acks_.Forget(key);
  }
}

void AggregatorNode::SendPending(const MapKey& key, double now_s) {
  auto it = incoming_.find(key);
  if (it == incoming_.end() || !publisher_) return;
  Incoming& in = it->second;
  // A tile is named only once it is on disk: the vehicle never sends it again.
  for (auto t = in.unspooled.begin(); t != in.unspooled.end();) {
    const core::Status saved = spool_.Save(key, t->first, t->second);
    if (!saved.ok()) {
      Refuse("spool: write failed", counters_.spool_errors,
             "cannot keep a received tile on disk (it is not acknowledged, the vehicle resends "
             "it): " +
                 saved.ToString());
      ++t;
      continue;
    }
    t = in.unspooled.erase(t);
  }
  AckFields ack;
  ack.key = key;
  ack.tile_count = in.tile_count;
  for (int32_t i : assembler_.Received(key.vehicle_id, key.sequence))
    if (!spool_.enabled() || spool_.Has(key, i)) ack.received.push_back(i);
  ack.outcome = fleetmap::tempmap_ack_t::PENDING;
  ack.map_version = aggregator_.store().version();
  Send(Link::kDownlink, lcmtypes::kTempMapAckChannel, AckMessage(ack, lcmtypes::ToUtime(now_s)));
  ++counters_.pending_acks_sent;
  acks_.Acked(key, now_s);
}

void AggregatorNode::SendFinal(const MapKey& key, int32_t tile_count, int8_t outcome,
                               const std::string& reason, uint64_t version, double now_s) {
  if (!publisher_) return;
  // A resent tile of a finished map has passed no layout check: its count may be absurd.
  tile_count = std::clamp(tile_count, 0, options_.assembler.max_tiles);
  AckFields ack;
  ack.key = key;
  ack.tile_count = tile_count;
  ack.received = AllTiles(tile_count);
  ack.outcome = outcome;
  ack.reason = reason;
  ack.map_version = version;
  Send(Link::kDownlink, lcmtypes::kTempMapAckChannel, AckMessage(ack, lcmtypes::ToUtime(now_s)));
}

void AggregatorNode::SendRequested(double now_s) {
  const RequestPlan plan = requests_.Take(now_s);
  const CurrentMapStore& store = aggregator_.store();
  if (plan.deltas_from) {
    for (uint64_t v = *plan.deltas_from; v < store.version(); ++v) {
      auto delta = store.Delta(v);
      if (!delta.ok()) {  // dropped meanwhile: a keyframe answers instead
        requests_.AddKeyframe({});
        break;
      }
      SendDelta(*delta, now_s);
      ++counters_.deltas_resent;
    }
  }
  if (plan.full_keyframe) SendKeyframe(nullptr, now_s);
  if (!plan.full_keyframe && !plan.keyframe_tiles.empty())
    SendKeyframe(&plan.keyframe_tiles, now_s);
}

void AggregatorNode::SendKeyframe(const std::vector<int32_t>* only, double now_s) {
  if (!publisher_) return;  // encoding a hundred tiles for nobody
  const auto messages = KeyframeMessages(aggregator_.store(), aggregator_.options().store.tiles,
                                         only, lcmtypes::ToUtime(now_s));
  for (const auto& m : messages) Send(Link::kDownlink, lcmtypes::kMapKeyframeChannel, m);
  counters_.keyframe_tiles_sent += static_cast<int64_t>(messages.size());
  ++counters_.keyframes_sent;
}

void AggregatorNode::SendDelta(const MapDelta& delta, double now_s) {
  if (!publisher_) return;
  const auto messages = DeltaMessages(delta, lcmtypes::ToUtime(now_s));
  for (const auto& m : messages) Send(Link::kDownlink, lcmtypes::kMapDeltaChannel, m);
  counters_.delta_tiles_sent += static_cast<int64_t>(messages.size());
}

void AggregatorNode::SendCandidates(double now_s) {
  if (!publisher_) return;
  const CurrentMapStore& store = aggregator_.store();
  for (const auto& m :
       CandidateMessages(store.candidates(), store.version(), lcmtypes::ToUtime(now_s)))
    Send(Link::kDownlink, lcmtypes::kMapCandidatesChannel, m);
  ++counters_.candidate_sets_sent;
}

void AggregatorNode::SendStatus(double now_s) {
  if (!publisher_) return;
  StatusFields s;
  s.process = options_.process_name;
  s.software_version = options_.software_version;
  s.map_version = aggregator_.store().version();
  s.state = state();
  s.authenticated = verifier_.enabled();
  s.counters = Named(counters_);
  s.counters.emplace_back("incomplete_maps", static_cast<int64_t>(incoming_.size()));
  s.counters.emplace_back("throttled_vehicles", limits_.throttled_vehicles());
  for (const auto& named : auth::Named(verifier_.counters())) s.counters.push_back(named);
  if (options_.recovery.id != 0 && now_s < options_.recovery.until_s) {
    s.counters.emplace_back(lcmtypes::kRecoveryIdCounter, options_.recovery.id);
    s.counters.emplace_back(lcmtypes::kRecoveredVersionCounter, options_.recovery.version);
  }
  Send(Link::kDownlink, lcmtypes::StatusChannel(options_.process_name),
       StatusMessage(s, lcmtypes::ToUtime(now_s)));
}

template <typename T>
void AggregatorNode::Send(Link link, const std::string& channel, const T& message) {
  if (!publisher_) return;
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  signer_.Seal(channel, bytes);
  if (static_cast<int>(bytes.size()) > options_.max_message_bytes) {
    Refuse("oversize " + channel, counters_.oversize_messages,
           channel + ": a message of " + std::to_string(bytes.size()) + " bytes (more than " +
               std::to_string(options_.max_message_bytes) + "): one lost packet loses it");
  }
  size_t& largest = largest_[channel];
  largest = std::max(largest, bytes.size());
  if (channel == lcmtypes::kTempMapAckChannel) ++counters_.acks_sent;
  if (!publisher_->Publish(link, channel, bytes)) {
    Refuse("publish failed", counters_.publish_failures,
           std::string("the ") + LinkName(link) + " refused a message on " + channel);
  }
}

std::string AggregatorNode::FinalLine() const {
  return node::FinalLine(aggregator_.store().version(), MapHash(aggregator_.store().current_map()),
                         counters_.maps_merged, counters_.maps_rejected);
}

}  // namespace fleetmap::aggregator::node
