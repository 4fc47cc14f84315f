// Where a complete temporary map becomes part of the current map, or is refused, and which
// acknowledgement that earns. Changes the current map only through Aggregator::Submit, with
// the map's own stamp (never the clock), so that a replay merges exactly as the live run did.
//
// A map is merged within its vehicle's merge rate (vehicle_limits.h); over it, the map is
// held (held_maps.h) and merged in the vehicle's order as the rate allows; with no room to
// hold it, it waits unacknowledged for the vehicle's resend. A merge is journaled before
// anything is acknowledged. When the journal cannot be written (a full disk) nothing is
// acknowledged: the map and every map completed after it wait in arrival order, so that a
// replay of the uplink merges them in that order too, and are merged once the journal writes
// again (tried every kPersistRetryS and at each resend of one of them).
// Once the outcome is journaled: the map's tiles leave the spool, TEMPMAP_ACK MERGED or
// REJECTED, MERGE_REPORT, and after a merge the MAP_DELTA and MAP_CANDIDATES; the map is
// remembered (handled_maps.h), so that a resend is answered DUPLICATE and never merged twice.
//
// Owns the complete maps waiting (held, unjournaled, or over the rate without room) and the
// record of finished maps.
#pragma once

#include <deque>
#include <map>
#include <optional>
#include <string>

#include "aggregator/aggregator.h"
#include "aggregator/node/handled_maps.h"
#include "aggregator/node/held_maps.h"
#include "aggregator/node/map_key.h"
#include "aggregator/node/map_publisher.h"
#include "aggregator/node/node_options.h"
#include "aggregator/node/node_reporting.h"
#include "aggregator/node/tile_spool.h"
#include "aggregator/node/vehicle_limits.h"
#include "core/map/temp_map.h"

namespace fleetmap::aggregator::node {

class MapCommitter {
 public:
  static constexpr double kPersistRetryS = 1.0;

  // Remembers every merge of the aggregator's history. Every reference outlives this.
  MapCommitter(Aggregator& aggregator, const AggregatorNodeOptions& options, TileSpool& spool,
               VehicleLimits& limits, MapPublisher& publisher, NodeReporting report);
  MapCommitter(const MapCommitter&) = delete;
  MapCommitter& operator=(const MapCommitter&) = delete;

  // The outcome of a map merged or rejected before (its tiles are a resend).
  std::optional<HandledMap> Handled(const MapKey& key) const { return handled_.Find(key); }
  // A tile of `key` arrived. True when the map is complete and waiting here: the tile needs no
  // assembling. A map waiting for the journal makes the journal be tried now; a map that
  // found no room to be held goes to Complete again, with the resent tile's stamp `map_s`.
  bool OnResend(const MapKey& key, double map_s, double now_s);
  // A complete map and the stamp of its completing tile: merged now, or kept waiting.
  void Complete(const MapKey& key, const core::TempMap& map, int32_t tile_count, double map_s,
                double now_s);
  // Tries the journal again when due, then merges the held maps whose turn has come.
  void Tick(double now_s);

  // A journal write failed and none has succeeded since.
  bool persist_failed() const { return persist_failed_; }
  int held_maps() const { return held_.size(); }
  size_t unjournaled_maps() const { return unpersisted_.size(); }

 private:
  struct Retry {
    core::TempMap map;
    int32_t tile_count = 0;
  };

  void Hold(const MapKey& key, const core::TempMap& map, int32_t tile_count, double map_s);
  void ReleaseHeld(double now_s);
  void Merge(const MapKey& key, const core::TempMap& map, int32_t tile_count, double map_s,
             double now_s);
  // False when the journal write failed (nothing changed, nothing acknowledged).
  bool TryMerge(const MapKey& key, const core::TempMap& map, int32_t tile_count, double map_s,
                double now_s);
  void JournalFailed(const MapKey& key, const core::Status& status);
  // The store refused the commit: a bug, not the vehicle's fault; the map is rejected.
  void SubmitFailed(const MapKey& key, int32_t tile_count, const core::Status& status,
                    double now_s);
  void Acknowledge(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                   const MergeReport& report, double map_s, double now_s);
  bool Unpersisted(const MapKey& key) const;
  void KeepUnpersisted(HeldMap map, double now_s);
  void RetryUnpersisted(double now_s);

  Aggregator& aggregator_;
  const AggregatorNodeOptions options_;
  TileSpool& spool_;
  VehicleLimits& limits_;
  MapPublisher& publisher_;
  NodeReporting report_;
  HandledMaps handled_;
  HeldMaps held_;                    // complete, over the vehicle's merge rate
  std::map<MapKey, Retry> retry_;    // complete, over the rate with no room to hold it
  std::deque<HeldMap> unpersisted_;  // complete, waiting for the journal (arrival order)
  double next_persist_try_s_ = 0.0;
  bool persist_failed_ = false;
};

}  // namespace fleetmap::aggregator::node
