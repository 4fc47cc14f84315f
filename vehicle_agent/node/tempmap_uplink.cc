#include "vehicle_agent/node/tempmap_uplink.h"

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "lcmtypes/channels.h"
#include "lcmtypes/status_counter.h"

namespace fleetmap::vehicle_agent::node {

TempMapUplink::TempMapUplink(const OutboxOptions& outbox, const core::PacerOptions& pacer,
                             CauseLog* log, AgentNodeCounters* counters)
    : state_dir_(outbox.state_dir),
      log_(log),
      counters_(counters),
      sequences_(outbox.state_dir),
      outbox_(outbox),
      sends_(pacer) {}

void TempMapUplink::StartNumberingAt(int32_t next) {
  reserved_ = next;
  ReserveFrom(next);
}

int TempMapUplink::ReloadPending(double now_s) {
  const int reloaded = outbox_.LoadPersisted(now_s);
  if (reloaded > 0) {
    log_->Info(std::to_string(reloaded) + " unacknowledged temporary map(s) reloaded from " +
               state_dir_ + ": sending them again");
  }
  return reloaded;
}

void TempMapUplink::Keep(const core::TempMap& map, double now_s) {
  ++counters_->tempmaps_closed;
  if (map.sequence >= reserved_) ReserveFrom(map.sequence);
  const core::Status added = outbox_.Add(map, now_s);
  if (!added.ok()) {
    log_->Once("outbox", "temporary map not kept: " + added.ToString());
    return;
  }
  log_->Info("temporary map " + std::to_string(map.sequence) +
             " closed: " + std::to_string(map.grid.geometry().width()) + " x " +
             std::to_string(map.grid.geometry().height()) + " cells over " +
             std::to_string(static_cast<int>(std::lround(map.end_s - map.start_s))) + " s");
}

// Numbers are reserved a block at a time, so that the fsync (which can stall the scan loop for
// seconds on a busy disk) comes once per block, not once per map; a restart skips the rest of
// a block, and the aggregator needs numbers that are unique, not consecutive.
void TempMapUplink::ReserveFrom(int32_t from) {
  const int32_t reserve = from < std::numeric_limits<int32_t>::max() - kSequenceBlock
                              ? from + kSequenceBlock
                              : std::numeric_limits<int32_t>::max();
  const core::Status stored = sequences_.Store(reserve);
  if (stored.ok()) {
    reserved_ = reserve;
  } else {
    log_->Once("sequence store", "cannot store the numbering: " + stored.ToString());
  }
}

core::Status TempMapUplink::OnAck(const fleetmap::tempmap_ack_t& ack) {
  if (ack.outcome < fleetmap::tempmap_ack_t::PENDING ||
      ack.outcome > fleetmap::tempmap_ack_t::DUPLICATE)
    return core::InvalidArgument("unknown ack outcome");
  std::vector<int32_t> received;
  for (int16_t i : ack.received_tiles) {
    if (i < 0 || i >= ack.tile_count)
      return core::OutOfRange("acknowledged tile index outside the map's tiles");
    received.push_back(i);
  }
  ++counters_->acks;
  const auto outcome = static_cast<AckOutcome>(ack.outcome);
  const size_t pending_before = outbox_.pending();
  outbox_.OnAck(ack.tempmap_seq, received, outcome, ack.map_version);
  const bool finished = outbox_.pending() < pending_before;
  // Tiles still waiting for the pacer that the aggregator has, or no longer needs, stay here.
  const std::set<int32_t> have(received.begin(), received.end());
  sends_.Drop(ack.tempmap_seq, [&](int32_t index) { return finished || have.count(index) > 0; });
  if (!finished) return core::OkStatus();  // PENDING, a repeated final ack, or a map not pending
  const std::string what = "temporary map " + std::to_string(ack.tempmap_seq);
  switch (outcome) {
    case AckOutcome::kMerged:
      ++counters_->maps_merged;
      log_->Info(what + " merged: map version " + std::to_string(ack.map_version));
      break;
    case AckOutcome::kRejected:
      ++counters_->maps_rejected;
      log_->Info(what + " rejected by the aggregator: " + ack.reason.substr(0, 200));
      break;
    case AckOutcome::kDuplicate:
      ++counters_->maps_duplicate;
      log_->Info(what + " was already handled by the aggregator (duplicate)");
      break;
    case AckOutcome::kPending:
      break;
  }
  return core::OkStatus();
}

// Answered once per recovery: the heartbeat repeats the recovery's counters every period.
void TempMapUplink::OnAggregatorStatus(const fleetmap::status_t& status, double now_s) {
  const int64_t recovery_id =
      lcmtypes::StatusCounter(status, lcmtypes::kRecoveryIdCounter).value_or(0);
  const int64_t recovered_version =
      lcmtypes::StatusCounter(status, lcmtypes::kRecoveredVersionCounter).value_or(-1);
  if (recovery_id == 0 || recovered_version < 0 || recovery_id == answered_recovery_) return;
  answered_recovery_ = recovery_id;
  const int resent = outbox_.ResendMergedAfter(recovered_version, now_s);
  log_->Info("the aggregator recovered its map at version " + std::to_string(recovered_version) +
             ": " + std::to_string(resent) + " merged temporary map(s) held here sent again");
}

std::vector<core::TempMapTile> TempMapUplink::TakeDue(double now_s, bool all) {
  sends_.Add(outbox_.Due(now_s));
  return sends_.Take(now_s, all);
}

}  // namespace fleetmap::vehicle_agent::node
