#include "aggregator/node/map_committer.h"

#include <algorithm>

#include "fleetmap/tempmap_ack_t.hpp"

namespace fleetmap::aggregator::node {

MapCommitter::MapCommitter(Aggregator& aggregator, const AggregatorNodeOptions& options,
                           TileSpool& spool, VehicleLimits& limits, MapPublisher& publisher,
                           NodeReporting report)
    : aggregator_(aggregator),
      options_(options),
      spool_(spool),
      limits_(limits),
      publisher_(publisher),
      report_(report),
      handled_(options_.max_remembered_rejections),
      held_(options_.max_held_maps) {
  handled_.LoadMerged(aggregator_.store().provenance());
}

bool MapCommitter::OnResend(const MapKey& key, double map_s, double now_s) {
  if (held_.Contains(key)) {  // waiting for its turn
    ++report_.counters.duplicates;
    return true;
  }
  if (Unpersisted(key)) {  // waiting for the journal: try the disk now
    ++report_.counters.duplicates;
    RetryUnpersisted(now_s);
    return true;
  }
  auto retry = retry_.find(key);
  if (retry == retry_.end()) return false;
  // A map over the merge rate found no room to be held and waited for this resend.
  const Retry again = retry->second;
  retry_.erase(retry);
  Complete(key, again.map, again.tile_count, map_s, now_s);
  return true;
}

void MapCommitter::Complete(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                            double map_s, double now_s) {
  if (!unpersisted_.empty()) {  // behind the maps waiting for the journal, in arrival order
    KeepUnpersisted({key, map, tile_count, map_s}, now_s);
    return;
  }
  if (!held_.Waiting(key.vehicle_id) && limits_.AllowMerge(key.vehicle_id, map_s, now_s)) {
    Merge(key, map, tile_count, map_s, now_s);
    return;
  }
  Hold(key, map, tile_count, map_s);
}

void MapCommitter::Hold(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                        double map_s) {
  const std::string over_rate = "vehicle '" + key.vehicle_id + "' completes more than " +
                                std::to_string(options_.limits.merges_per_min) + " maps per minute";
  if (held_.Hold({key, map, tile_count, map_s})) {
    report_.Refuse("TEMPMAP: merge rate", report_.counters.throttled_merges,
                   over_rate + ": " + key.ToString() +
                       " and its next maps are held, merged in order as the rate allows");
    return;
  }
  report_.Refuse("TEMPMAP: held maps full", report_.counters.throttled_merges,
                 over_rate + " and " + std::to_string(options_.max_held_maps) +
                     " maps are held: " + key.ToString() + " waits unacknowledged for a resend");
  if (static_cast<int>(retry_.size()) < options_.max_retry_maps) retry_[key] = {map, tile_count};
}

void MapCommitter::Tick(double now_s) {
  if (!unpersisted_.empty() && now_s >= next_persist_try_s_) RetryUnpersisted(now_s);
  // Held maps wait behind any map the journal refused, which keeps the arrival order.
  if (unpersisted_.empty()) ReleaseHeld(now_s);
}

void MapCommitter::ReleaseHeld(double now_s) {
  const auto allow = [&](const std::string& vehicle, double map_s) {
    return limits_.AllowMerge(vehicle, map_s, now_s);
  };
  for (const HeldMap& m : held_.Release(allow)) Merge(m.key, m.map, m.tile_count, m.map_s, now_s);
}

void MapCommitter::Merge(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                         double map_s, double now_s) {
  if (TryMerge(key, map, tile_count, map_s, now_s)) return;
  limits_.RefundMerge(key.vehicle_id);  // a merge the disk refused costs the vehicle nothing
  KeepUnpersisted({key, map, tile_count, map_s}, now_s);
}

bool MapCommitter::TryMerge(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                            double map_s, double now_s) {
  auto report = aggregator_.Submit(map, map_s);
  if (!report.ok() && report.status().code() == core::StatusCode::kIoError) {
    JournalFailed(key, report.status());
    return false;
  }
  spool_.Remove(key);
  if (report.ok()) {
    Acknowledge(key, map, tile_count, *report, map_s, now_s);
  } else {
    SubmitFailed(key, tile_count, report.status(), now_s);
  }
  return true;
}

void MapCommitter::JournalFailed(const MapKey& key, const core::Status& status) {
  ++report_.counters.persist_errors;
  if (!persist_failed_) {  // one line per outage, however many maps wait
    report_.log.Warning("merge of " + key.ToString() +
                        " not journaled, not acknowledged: " + status.ToString() +
                        "; it and the maps after it are kept and merged in order once the "
                        "journal writes again (tried every " +
                        std::to_string(kPersistRetryS) + " s and at each resend)");
  }
  persist_failed_ = true;
}

void MapCommitter::SubmitFailed(const MapKey& key, int32_t tile_count, const core::Status& status,
                                double now_s) {
  ++report_.counters.submit_errors;
  report_.log.Warning("merge of " + key.ToString() + " failed: " + status.ToString());
  handled_.Rejected(key, aggregator_.store().version());
  ++report_.counters.maps_rejected;
  publisher_.SendFinalAck(key, tile_count, fleetmap::tempmap_ack_t::REJECTED,
                          "internal error: " + status.ToString(), aggregator_.store().version(),
                          now_s);
}

void MapCommitter::Acknowledge(const MapKey& key, const core::TempMap& map, int32_t tile_count,
                               const MergeReport& report, double map_s, double now_s) {
  if (report.accepted) persist_failed_ = false;
  if (!report.warning.empty()) {
    ++report_.counters.snapshot_errors;
    report_.log.Warning(report.warning);
  }
  if (report.accepted) {
    ++report_.counters.maps_merged;
    handled_.Merged(key, report.version);
    publisher_.SendFinalAck(key, tile_count, fleetmap::tempmap_ack_t::MERGED, "", report.version,
                            now_s);
  } else {
    ++report_.counters.maps_rejected;
    handled_.Rejected(key, report.version);
    publisher_.SendFinalAck(key, tile_count, fleetmap::tempmap_ack_t::REJECTED, report.reason_text,
                            report.version, now_s);
  }
  publisher_.SendMergeReport(report, map.anchor_in_map, map_s);
  if (report.accepted) {
    publisher_.SendDelta(report.delta, now_s);
    publisher_.SendCandidates(now_s);
  }
}

bool MapCommitter::Unpersisted(const MapKey& key) const {
  return std::any_of(unpersisted_.begin(), unpersisted_.end(),
                     [&](const HeldMap& m) { return m.key == key; });
}

void MapCommitter::KeepUnpersisted(HeldMap map, double now_s) {
  if (unpersisted_.empty()) next_persist_try_s_ = now_s + kPersistRetryS;
  if (static_cast<int>(unpersisted_.size()) < options_.max_retry_maps) {
    unpersisted_.push_back(std::move(map));
    return;
  }
  report_.Refuse("TEMPMAP: journal backlog full", report_.counters.persist_backlog_full,
                 std::to_string(options_.max_retry_maps) + " maps wait for the journal: " +
                     map.key.ToString() + " waits unacknowledged for the vehicle's resend");
}

void MapCommitter::RetryUnpersisted(double now_s) {
  while (!unpersisted_.empty()) {
    const HeldMap& m = unpersisted_.front();
    if (!TryMerge(m.key, m.map, m.tile_count, m.map_s, now_s)) {
      next_persist_try_s_ = now_s + kPersistRetryS;
      return;
    }
    unpersisted_.pop_front();
  }
}

}  // namespace fleetmap::aggregator::node
