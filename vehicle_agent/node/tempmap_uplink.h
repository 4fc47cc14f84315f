// Temporary maps on their way to the aggregator, from the moment a map closes until it is
// acknowledged: numbered (the number stored before the map leaves, SequenceStore), kept in the
// outbox (resent until acknowledged, TempMapOutbox), their tiles paced out (TileSendQueue),
// and the merged maps the aggregator lost in a recovery sent again, once per recovery. The
// node decodes the messages and sends the tiles TakeDue returns.
#pragma once

#include <cstdint>
#include <vector>

#include "core/codec/send_pacer.h"
#include "core/map/temp_map.h"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "vehicle_agent/node/agent_counters.h"
#include "vehicle_agent/node/node_io.h"
#include "vehicle_agent/node/sequence_store.h"
#include "vehicle_agent/node/tile_send_queue.h"
#include "vehicle_agent/tempmap_outbox.h"

namespace fleetmap::vehicle_agent::node {

class TempMapUplink {
 public:
  // Temporary-map numbers reserved on disk at a time: one fsync per 32 maps (every minute or
  // two at one map per 3 s).
  static constexpr int32_t kSequenceBlock = 32;

  // `log` and `counters` (tempmaps_closed, acks, maps_merged, maps_rejected, maps_duplicate)
  // outlive the uplink. outbox.state_dir holds the numbering and the pending maps.
  TempMapUplink(const OutboxOptions& outbox, const core::PacerOptions& pacer, CauseLog* log,
                AgentNodeCounters* counters);

  // At start, `next` being the number the next map gets (SequenceStore::Load): its block is
  // reserved now, not on the scan loop.
  void StartNumberingAt(int32_t next);
  // Reloads the maps an earlier run left unacknowledged in the state folder; returns how many.
  int ReloadPending(double now_s);
  // A closed map: its number goes on disk first (a crash cannot reuse it), then the outbox
  // holds it until it is acknowledged.
  void Keep(const core::TempMap& map, double now_s);
  // An acknowledgement naming this vehicle. InvalidArgument for an unknown outcome, OutOfRange
  // for a tile index outside the map's tiles: then nothing changes.
  core::Status OnAck(const fleetmap::tempmap_ack_t& ack);
  // The aggregator's heartbeat: a recovery it names for the first time (recovery_id, with the
  // version it recovered) makes the merged maps held here from after that version pending again.
  void OnAggregatorStatus(const fleetmap::status_t& status, double now_s);
  // The tiles to send now, oldest first: the outbox's due tiles join the pacing queue and as
  // many leave as the pacer allows (all of them when `all`: at exit).
  std::vector<core::TempMapTile> TakeDue(double now_s, bool all = false);

  const TempMapOutbox& outbox() const { return outbox_; }
  size_t tiles_queued() const { return sends_.size(); }
  // Numbers below this are on disk as used (reserved kSequenceBlock at a time).
  int32_t reserved() const { return reserved_; }

 private:
  // Stores `from` + a block as the next number.
  void ReserveFrom(int32_t from);

  const std::string state_dir_;
  CauseLog* const log_;
  AgentNodeCounters* const counters_;
  SequenceStore sequences_;
  int32_t reserved_ = 1;
  TempMapOutbox outbox_;
  TileSendQueue sends_;
  int64_t answered_recovery_ = 0;  // the aggregator's last recovery this vehicle answered
};

}  // namespace fleetmap::vehicle_agent::node
