#include "aggregator/node/temp_map_receiver.h"

#include <algorithm>
#include <set>

#include "fleetmap/tempmap_ack_t.hpp"
#include "fleetmap/tempmap_tile_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::aggregator::node {

TempMapReceiver::TempMapReceiver(const AggregatorNodeOptions& options, TileSpool& spool,
                                 VehicleLimits& limits, MapCommitter& committer,
                                 MapPublisher& publisher, NodeReporting report)
    : options_(options),
      spool_(spool),
      limits_(limits),
      committer_(committer),
      publisher_(publisher),
      report_(report),
      assembler_(options_.assembler),
      acks_(options_.pending_ack_interval_s) {}

void TempMapReceiver::RestoreSpool(double now_s) {
  int bad_files = 0;
  const std::vector<SpooledTile> tiles = spool_.LoadAll(&bad_files);
  report_.counters.spool_errors += bad_files;
  int restored = 0;
  std::set<MapKey> dropped;
  for (const SpooledTile& s : tiles) {
    if (dropped.count(s.key)) continue;
    const core::Result<StampedTile> kept = ReadKept(s);
    if (!kept.ok()) {
      DropUnreadable(s.key);
      dropped.insert(s.key);
      continue;
    }
    if (committer_.Handled(s.key)) {  // merged just before the last run stopped
      spool_.Remove(s.key);
      continue;
    }
    AddTile(kept->tile, s.bytes, kept->map_s, /*from_spool=*/true, now_s);
    ++restored;
  }
  if (restored > 0)
    report_.log.Info("restored " + std::to_string(restored) +
                     " acknowledged tiles of incomplete maps");
}

// The vehicle will not send an acknowledged tile again: the map cannot complete.
void TempMapReceiver::DropUnreadable(const MapKey& key) {
  ++report_.counters.spool_errors;
  report_.log.Warning("tile spool: dropping " + key.ToString() +
                      ": a kept tile is unreadable, the map cannot be completed");
  Drop(key);
}

// A spool file's tile: files can rot or be edited, so it is checked like a received one, and
// against the name it was kept under.
core::Result<TempMapReceiver::StampedTile> TempMapReceiver::ReadKept(const SpooledTile& s) {
  auto msg =
      lcmtypes::Decode<fleetmap::tempmap_tile_t>(s.bytes.data(), static_cast<int>(s.bytes.size()));
  if (!msg.ok()) return msg.status();
  auto tile = lcmtypes::FromMessage(*msg);
  if (!tile.ok()) return tile.status();
  if (tile->vehicle_id != s.key.vehicle_id || tile->sequence != s.key.sequence ||
      tile->index != s.index)
    return core::InvalidArgument("not the tile its file name says");
  return StampedTile{std::move(*tile), lcmtypes::FromUtime(msg->utime)};
}

void TempMapReceiver::OnTile(const std::string& channel, const void* data, int size, double now_s) {
  const std::optional<StampedTile> received = Believed(channel, data, size);
  if (!received) return;
  // Counted once the tile is authentic and valid: forged or broken tiles on a vehicle's
  // channel must not use up its rate.
  if (Throttled(received->tile.vehicle_id, now_s)) return;
  const auto* bytes = static_cast<const uint8_t*>(data);
  AddTile(received->tile, std::vector<uint8_t>(bytes, bytes + size), received->map_s,
          /*from_spool=*/false, now_s);
}

std::optional<TempMapReceiver::StampedTile> TempMapReceiver::Believed(const std::string& channel,
                                                                      const void* data, int size) {
  auto msg = lcmtypes::Decode<fleetmap::tempmap_tile_t>(data, size);
  if (!msg.ok()) {
    report_.Refuse("TEMPMAP: malformed", report_.counters.malformed_messages,
                   channel + ": not a tempmap_tile_t: " + msg.status().ToString());
    return std::nullopt;
  }
  if (msg->vehicle_id != lcmtypes::ChannelSuffix(channel, lcmtypes::kTempMapPrefix)) {
    report_.Refuse("TEMPMAP: wrong vehicle id", report_.counters.wrong_vehicle_id,
                   channel + ": a tile of vehicle '" +
                       msg->vehicle_id.substr(0, kMaxUplinkVehicleIdBytes) +
                       "' refused: a vehicle sends only its own maps, on its own channel");
    return std::nullopt;
  }
  auto tile = lcmtypes::FromMessage(*msg);
  if (!tile.ok()) {
    report_.Refuse("TEMPMAP: invalid tile", report_.counters.invalid_tiles,
                   channel + ": invalid tile: " + tile.status().ToString());
    return std::nullopt;
  }
  return StampedTile{std::move(*tile), lcmtypes::FromUtime(msg->utime)};
}

bool TempMapReceiver::Throttled(const std::string& vehicle, double now_s) {
  if (limits_.AllowTile(vehicle, now_s)) return false;
  ++report_.counters.throttled_tiles;
  if (limits_.FirstThrottle(vehicle)) {
    report_.log.Warning("vehicle '" + vehicle.substr(0, kMaxUplinkVehicleIdBytes) +
                        "' sends more than " + std::to_string(options_.limits.tiles_per_s) +
                        " tiles/s: throttled, its tiles over the rate are dropped (other "
                        "vehicles are not affected; counted in throttled_tiles)");
  }
  return true;
}

void TempMapReceiver::AddTile(const core::TempMapTile& tile, const std::vector<uint8_t>& bytes,
                              double map_s, bool from_spool, double now_s) {
  const MapKey key{tile.vehicle_id, tile.sequence};
  ++report_.counters.tiles_received;
  if (Finished(key, tile.count, now_s)) return;
  if (committer_.OnResend(key, map_s, now_s)) return;
  if (!Room(key)) return;
  const std::vector<int32_t> before = assembler_.Received(key.vehicle_id, key.sequence);
  const bool repeated = std::binary_search(before.begin(), before.end(), tile.index);
  auto added = assembler_.Add(tile);
  if (!added.ok()) {
    report_.Refuse("TEMPMAP: inconsistent tile", report_.counters.inconsistent_tiles,
                   "tile " + std::to_string(tile.index) + " of " + key.ToString() +
                       " refused: " + added.status().ToString());
    return;
  }
  if (repeated) ++report_.counters.tiles_repeated;
  if (!added->has_value()) {
    Incomplete(key, tile, bytes, repeated, from_spool, now_s);
    return;
  }
  incoming_.erase(key);
  acks_.Forget(key);
  ++report_.counters.maps_completed;
  committer_.Complete(key, **added, tile.count, map_s, now_s);
}

bool TempMapReceiver::Finished(const MapKey& key, int32_t tile_count, double now_s) {
  const auto handled = committer_.Handled(key);
  if (!handled) return false;
  ++report_.counters.duplicates;
  if (acks_.FinalAckDue(key, now_s)) {
    publisher_.SendFinalAck(key, tile_count, fleetmap::tempmap_ack_t::DUPLICATE, "",
                            handled->version, now_s);
  }
  return true;
}

bool TempMapReceiver::Room(const MapKey& key) {
  if (incoming_.count(key)) return true;
  if (PendingMaps(key.vehicle_id) >= options_.limits.max_pending_maps_per_vehicle) {
    report_.Refuse("TEMPMAP: vehicle's maps full", report_.counters.vehicle_maps_full,
                   "vehicle '" + key.vehicle_id + "' has " +
                       std::to_string(options_.limits.max_pending_maps_per_vehicle) +
                       " incomplete temporary maps; " + key.ToString() +
                       " has to wait for its resend");
    return false;
  }
  if (static_cast<int>(incoming_.size()) >= options_.assembler.max_pending_maps) {
    report_.Refuse("TEMPMAP: too many maps", report_.counters.assembler_full,
                   "too many temporary maps being received at once (" +
                       std::to_string(options_.assembler.max_pending_maps) + "); " +
                       key.ToString() + " has to wait for the vehicle's resend");
    return false;
  }
  return true;
}

int TempMapReceiver::PendingMaps(const std::string& vehicle) const {
  int n = 0;
  for (const auto& [key, in] : incoming_) n += key.vehicle_id == vehicle;
  return n;
}

void TempMapReceiver::Incomplete(const MapKey& key, const core::TempMapTile& tile,
                                 const std::vector<uint8_t>& bytes, bool repeated, bool from_spool,
                                 double now_s) {
  Incoming& in = incoming_[key];
  in.tile_count = tile.count;
  if (from_spool) {
    acks_.Restore(key, now_s);
    return;
  }
  if (!repeated && spool_.enabled()) in.unspooled[tile.index] = bytes;
  if (acks_.OnTile(key, repeated, now_s)) SendPending(key, now_s);
}

void TempMapReceiver::Tick(double now_s) {
  for (const MapKey& key : acks_.Due(now_s)) SendPending(key, now_s);
  DropStale(now_s);
}

void TempMapReceiver::SendPending(const MapKey& key, double now_s) {
  auto it = incoming_.find(key);
  if (it == incoming_.end() || !publisher_.enabled()) return;
  SaveUnspooled(key, it->second);
  std::vector<int32_t> received;
  for (int32_t i : assembler_.Received(key.vehicle_id, key.sequence))
    if (!spool_.enabled() || spool_.Has(key, i)) received.push_back(i);
  publisher_.SendPendingAck(key, it->second.tile_count, std::move(received), now_s);
  acks_.Acked(key, now_s);
}

// A tile is named in an acknowledgement only once it is on disk: the vehicle never sends it
// again.
void TempMapReceiver::SaveUnspooled(const MapKey& key, Incoming& in) {
  for (auto t = in.unspooled.begin(); t != in.unspooled.end();) {
    const core::Status saved = spool_.Save(key, t->first, t->second);
    if (!saved.ok()) {
      report_.Refuse("spool: write failed", report_.counters.spool_errors,
                     "cannot keep a received tile on disk (it is not acknowledged, the vehicle "
                     "resends it): " +
                         saved.ToString());
      ++t;
      continue;
    }
    t = in.unspooled.erase(t);
  }
}

void TempMapReceiver::DropStale(double now_s) {
  for (const MapKey& key : acks_.Stale(now_s, options_.pending_map_timeout_s)) {
    ++report_.counters.maps_evicted;
    report_.log.Info("dropping incomplete temporary map " + key.ToString() + ": no tile for " +
                     std::to_string(options_.pending_map_timeout_s) + " s");
    Drop(key);
  }
}

void TempMapReceiver::Drop(const MapKey& key) {
  assembler_.Drop(key.vehicle_id, key.sequence);
  spool_.Remove(key);
  incoming_.erase(key);
  acks_.Forget(key);
}

}  // namespace fleetmap::aggregator::node
