// Turns a vehicle's TEMPMAP_<id> tiles into complete temporary maps for the committer
// (map_committer.h). A tile is believed once it decodes, names the channel's vehicle and
// passes its own checks; only then does it count against the vehicle's tile rate
// (vehicle_limits.h), so that forged or broken tiles cannot use up a vehicle's rate. A tile
// of a map the committer has finished is answered DUPLICATE (at most once per
// pending_ack_interval_s), one of a map it still holds goes to it; any other joins its map
// (core::TempMapAssembler), within the bounds on incomplete maps per vehicle and overall.
// An incomplete map is acknowledged PENDING (ack_schedule.h) naming only tiles already kept
// on disk (tile_spool.h): the vehicle never resends a tile it saw acknowledged, so a restart
// must still have it. A map that received no tile for pending_map_timeout_s is dropped.
// Owns the maps being assembled and their acknowledgement times; fills the spool, which the
// committer empties once a map's outcome is journaled.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "aggregator/node/ack_schedule.h"
#include "aggregator/node/map_committer.h"
#include "aggregator/node/map_key.h"
#include "aggregator/node/map_publisher.h"
#include "aggregator/node/node_options.h"
#include "aggregator/node/node_reporting.h"
#include "aggregator/node/tile_spool.h"
#include "aggregator/node/vehicle_limits.h"
#include "core/codec/temp_map_tiles.h"
#include "core/result.h"

namespace fleetmap::aggregator::node {

class TempMapReceiver {
 public:
  // Every reference outlives this.
  TempMapReceiver(const AggregatorNodeOptions& options, TileSpool& spool, VehicleLimits& limits,
                  MapCommitter& committer, MapPublisher& publisher, NodeReporting report);
  TempMapReceiver(const TempMapReceiver&) = delete;
  TempMapReceiver& operator=(const TempMapReceiver&) = delete;

  // The tiles an earlier run kept in the spool go back into their maps, unacknowledged until
  // new tiles come; a map with an unreadable tile can never complete and is dropped.
  void RestoreSpool(double now_s);
  // The payload of a TEMPMAP_<id> message on `channel`, received at `now_s`.
  void OnTile(const std::string& channel, const void* data, int size, double now_s);
  // The PENDING acknowledgements due, then the incomplete maps gone silent are dropped.
  void Tick(double now_s);

  size_t incomplete_maps() const { return incoming_.size(); }

 private:
  struct Incoming {
    int32_t tile_count = 0;
    std::map<int32_t, std::vector<uint8_t>> unspooled;  // received, not yet on disk
  };

  struct StampedTile {
    core::TempMapTile tile;
    double map_s = 0.0;  // the tile's own stamp, which the merge goes by
  };

  static core::Result<StampedTile> ReadKept(const SpooledTile& s);
  void DropUnreadable(const MapKey& key);
  // Decoded, from the channel's vehicle, and valid; refused (counted, logged) otherwise.
  std::optional<StampedTile> Believed(const std::string& channel, const void* data, int size);
  bool Throttled(const std::string& vehicle, double now_s);
  // `bytes` is the tile's message, for the spool.
  void AddTile(const core::TempMapTile& tile, const std::vector<uint8_t>& bytes, double map_s,
               bool from_spool, double now_s);
  // A map merged or rejected before: true, and answered DUPLICATE when that is due.
  bool Finished(const MapKey& key, int32_t tile_count, double now_s);
  // False (refused) when a new map would exceed the vehicle's or the node's incomplete maps.
  bool Room(const MapKey& key);
  int PendingMaps(const std::string& vehicle) const;
  void Incomplete(const MapKey& key, const core::TempMapTile& tile,
                  const std::vector<uint8_t>& bytes, bool repeated, bool from_spool, double now_s);
  void SendPending(const MapKey& key, double now_s);
  void SaveUnspooled(const MapKey& key, Incoming& in);
  void DropStale(double now_s);
  void Drop(const MapKey& key);

  const AggregatorNodeOptions options_;
  TileSpool& spool_;
  VehicleLimits& limits_;
  MapCommitter& committer_;
  MapPublisher& publisher_;
  NodeReporting report_;
  core::TempMapAssembler assembler_;
  AckSchedule acks_;
  std::map<MapKey, Incoming> incoming_;  // maps being assembled
};

}  // namespace fleetmap::aggregator::node
