// The vehicle's side of the map catch-up protocol (docs/agent_process.md): keeps the replica
// of the aggregator's current map (core::MapReplica) and decides when to send MAP_REQUEST.
//   - seeded with the static map file (version 0 at the aggregator): one request with
//     have_version 0 at start, so that the aggregator resends the deltas merged since;
//   - without a map: a request with have_version -1 naming the keyframe tiles it lacks, once
//     per period while they are few enough to list (the aggregator keeps each asked tile
//     once, so asking again costs only what was lost); when more (the whole map), again only
//     after a period in which no keyframe tile came: while tiles come, the answer is arriving
//     (the aggregator sends within its downlink's byte budget, so a large map takes seconds),
//     and asking for the whole map again would send again what already arrived;
//   - a version gap (a delta for a version after one we missed), or the aggregator's
//     heartbeat showing a newer version for a whole period: a request with our version;
//   - the heartbeat showing an older version than ours for two periods: the aggregator
//     restarted without its state and numbers versions anew. The replica is dropped and the
//     aggregator's map asked for (have_version -1); localization keeps its map until then.
// Keyframes of another map geometry are refused: they belong to another site's map. Free of
// LCM: tiles come in as core types and time is passed in.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "core/map/map_replica.h"

namespace fleetmap::vehicle_agent::node {

struct MapFollowerOptions {
  int tile_size_cells = 64;        // the tiling of the aggregator's deltas, cells, >= 4
  double request_period_s = 1.0;   // at most one MAP_REQUEST per period, s, > 0
  int max_buffered_versions = 16;  // deltas held while waiting for a missed one, >= 1
  // A request names at most this many tiles (4 bytes each: 8 KB), >= 0; a vehicle lacking
  // more asks for the whole map.
  int max_request_tiles = 2048;
  core::Status Validate() const;
};

struct MapFollowerCounters {
  int64_t keyframe_tiles = 0;        // accepted into the replica
  int64_t delta_tiles = 0;           // accepted into the replica
  int64_t versions_applied = 0;      // versions that became the map (a keyframe counts one)
  int64_t requests = 0;              // MAP_REQUESTs asked for
  int64_t stale_tiles = 0;           // tiles of versions we already hold (normal after a keyframe)
  int64_t wrong_geometry_tiles = 0;  // keyframe tiles of another map geometry: refused
  int64_t refused_tiles = 0;         // tiles the replica refused (corrupt, inconsistent, too many)
  int64_t resets = 0;                // the aggregator's versions went back: replica dropped
};

class MapFollower {
 public:
  explicit MapFollower(const MapFollowerOptions& options);

  // Starts from a map the vehicle holds (the static map file) at `version`.
  core::Status Seed(core::OccupancyGrid map, int32_t version);
  // Each returns true when the tile made a new version the map (then map() and version()
  // are the new ones), false when it was kept or is old news, an error when refused.
  core::Result<bool> OnKeyframeTile(const core::KeyframeTile& tile);
  core::Result<bool> OnDeltaTile(const core::DeltaTile& tile);
  // The aggregator's heartbeat: the version it holds.
  void OnRemoteVersion(int32_t version, double now_s);

  // have_version for a MAP_REQUEST to send now (-1: no map), or nothing. Counts the request.
  // Drops the replica first when the heartbeat says the aggregator's versions went back.
  std::optional<int32_t> RequestDue(double now_s);
  // The keyframe tiles the request just due names (linear indices, ascending); empty: the
  // whole map, or none when it has a map (deltas since have_version then).
  const std::vector<int32_t>& request_tiles() const { return request_tiles_; }

  bool has_map() const { return replica_.has_map(); }
  const core::OccupancyGrid& map() const { return replica_.map(); }
  int32_t version() const { return replica_.version(); }
  // Where the map changed since the last call (core::MapReplica::TakeChanged).
  core::CellWindow TakeChanged() { return replica_.TakeChanged(); }
  const MapFollowerCounters& counters() const { return counters_; }

 private:
  bool WantsRequest(double now_s) const;
  // Counts an added tile; version_before -1: a keyframe (one new version).
  core::Result<bool> Counted(core::Result<bool> result, int64_t& accepted, int32_t version_before);

  const MapFollowerOptions options_;
  core::MapReplica replica_;
  std::optional<core::GridGeometry> geometry_;  // of the seed or the first keyframe
  bool asked_once_ = false;
  int64_t keyframe_tiles_at_last_request_ = 0;  // counters_.keyframe_tiles then
  std::vector<int32_t> request_tiles_;
  double last_request_s_ = -std::numeric_limits<double>::infinity();
  int32_t remote_version_ = -1;
  double remote_ahead_since_s_ = 0.0;   // when the heartbeat first showed a newer version
  bool remote_behind_ = false;          // the heartbeat shows an older version than ours ...
  double remote_behind_since_s_ = 0.0;  // ... since then
  MapFollowerCounters counters_;
};

}  // namespace fleetmap::vehicle_agent::node
