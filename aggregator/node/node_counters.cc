#include "aggregator/node/node_counters.h"

namespace fleetmap::aggregator::node {

NamedCounters Named(const NodeCounters& c) {
  return {{"messages", c.messages},
          {"tiles_received", c.tiles_received},
          {"tiles_repeated", c.tiles_repeated},
          {"maps_completed", c.maps_completed},
          {"maps_merged", c.maps_merged},
          {"maps_rejected", c.maps_rejected},
          {"duplicates", c.duplicates},
          {"maps_evicted", c.maps_evicted},
          {"malformed_messages", c.malformed_messages},
          {"invalid_tiles", c.invalid_tiles},
          {"inconsistent_tiles", c.inconsistent_tiles},
          {"assembler_full", c.assembler_full},
          {"wrong_vehicle_id", c.wrong_vehicle_id},
          {"unknown_channel", c.unknown_channel},
          {"ignored_messages", c.ignored_messages},
          {"requests", c.requests},
          {"bad_requests", c.bad_requests},
          {"keyframes_sent", c.keyframes_sent},
          {"keyframe_tiles_sent", c.keyframe_tiles_sent},
          {"delta_tiles_sent", c.delta_tiles_sent},
          {"deltas_resent", c.deltas_resent},
          {"acks_sent", c.acks_sent},
          {"pending_acks_sent", c.pending_acks_sent},
          {"merge_reports_sent", c.merge_reports_sent},
          {"persist_errors", c.persist_errors},
          {"snapshot_errors", c.snapshot_errors},
          {"spool_errors", c.spool_errors},
          {"submit_errors", c.submit_errors},
          {"publish_failures", c.publish_failures},
          {"oversize_messages", c.oversize_messages},
          {"oversize_received", c.oversize_received},
          {"throttled_tiles", c.throttled_tiles},
          {"throttled_merges", c.throttled_merges},
          {"vehicle_maps_full", c.vehicle_maps_full},
          {"auth_refused", c.auth_refused},
          {"seen_free_reports", c.seen_free_reports},
          {"bad_seen_free", c.bad_seen_free},
          {"candidates_dropped", c.candidates_dropped},
          {"candidate_sets_sent", c.candidate_sets_sent}};
}

}  // namespace fleetmap::aggregator::node
