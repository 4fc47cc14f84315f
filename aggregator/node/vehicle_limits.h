// Per-vehicle bounds of the aggregator: what one vehicle may cost the server, so that a
// vehicle that floods (a bug, a broken radio, an attacker with a vehicle's key) is throttled
// while the others are served as before. Each vehicle has two token buckets: tiles received,
// and complete maps handed to the merge. The merge bucket runs on the maps' own stamps, so
// that a log replayed faster than real, or a vehicle's backlog after an outage, is merged as
// it was made; a host-clock bound keeps forged stamps from refilling it faster than
// max_replay_speed times real time.
#pragma once

#include <map>
#include <string>

#include "core/result.h"

namespace fleetmap::aggregator::node {

struct VehicleLimitOptions {
  // A received message larger than this is refused before it is decoded, bytes >= 1024. A
  // temporary-map tile is at most ~4.2 KB (64 x 64 int8 cells, incompressible).
  int max_received_bytes = 65536;
  // Incomplete temporary maps one vehicle may have at once, maps >= 1 (all vehicles
  // together: assembler.max_pending_maps, 32), so one vehicle cannot take every slot. Not
  // much fewer: on a lossy link most maps miss a tile or two and wait for a resend while the
  // vehicle closes a new one every few seconds, so a small limit keeps a vehicle at it and
  // refuses its new maps (docs/experiments/2026-12-01-lossy-links.md).
  int max_pending_maps_per_vehicle = 16;
  // Tiles one vehicle may send, tiles/s > 0, after a burst of tile_burst (>= 1). A 20 m
  // temporary map is 49 tiles; an agent's uplink pacer sends at most 400 tiles/s.
  double tiles_per_s = 400.0;
  double tile_burst = 1000.0;
  // Complete maps of one vehicle that go to the merge, per minute of the maps' stamps > 0,
  // after a burst of merge_burst (>= 1). A map over the rate is held and merged later, in the
  // vehicle's order, once the rate allows (AggregatorNodeOptions::max_held_maps). A vehicle
  // closes a temporary map at most every divergence.min_duration_s (2 s): 30 a minute.
  double merges_per_min = 60.0;
  double merge_burst = 20.0;
  // The stamps may advance up to this many times faster than the host's clock and still
  // count (a replay at 10x, a backlog sent at once), >= 1; beyond, the host's clock times
  // this refills the bucket.
  double max_replay_speed = 20.0;
  // Vehicles tracked at once, >= 1; beyond, idle ones are forgotten first.
  int max_vehicles = 1024;
  core::Status Validate() const;
};

class VehicleLimits {
 public:
  explicit VehicleLimits(const VehicleLimitOptions& options) : options_(options) {}

  // False when `vehicle` is over its tile rate (the tile is dropped).
  bool AllowTile(const std::string& vehicle, double now_s);
  // False when `vehicle` is over its merge rate (the map is held); `map_s` is the map's stamp.
  bool AllowMerge(const std::string& vehicle, double map_s, double now_s);
  // Gives back the merge AllowMerge granted (the merge did not happen: the disk refused it).
  void RefundMerge(const std::string& vehicle);
  // True the first time `vehicle` is throttled, for a single log line per vehicle.
  bool FirstThrottle(const std::string& vehicle);
  // Vehicles throttled at least once since the start.
  int throttled_vehicles() const { return static_cast<int>(throttled_.size()); }

 private:
  struct Bucket {
    double tokens = 0;
    double last_s = 0;
    double last_stamp_s = 0;  // the newest stamp counted (stamped buckets only)
    bool stamped = false;     // last_stamp_s is set
  };
  struct Vehicle {
    Bucket tiles;
    Bucket merges;
  };
  Vehicle* Find(const std::string& vehicle, double now_s);
  // Refills `elapsed_s` worth of tokens (up to `burst`) and takes one if there is one.
  static bool Spend(Bucket& b, double elapsed_s, double rate_per_s, double burst);
  static bool Take(Bucket& b, double rate_per_s, double burst, double now_s);
  bool TakeStamped(Bucket& b, double stamp_s, double now_s) const;

  VehicleLimitOptions options_;
  std::map<std::string, Vehicle> vehicles_;
  std::map<std::string, bool> throttled_;
};

}  // namespace fleetmap::aggregator::node
