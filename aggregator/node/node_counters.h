// What the aggregator node has seen and done, as published in STATUS_aggregator. Every
// message that is refused raises exactly one counter named after its cause.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace fleetmap::aggregator::node {

struct NodeCounters {
  int64_t messages = 0;             // handed to the node, any channel
  int64_t tiles_received = 0;       // valid temporary-map tiles (repeats included)
  int64_t tiles_repeated = 0;       // a tile the node already held
  int64_t maps_completed = 0;       // temporary maps whose last tile arrived
  int64_t maps_merged = 0;          // accepted: a new map version
  int64_t maps_rejected = 0;        // complete but not merged (MERGE_REPORT says why)
  int64_t duplicates = 0;           // tiles of maps already merged or rejected
  int64_t maps_evicted = 0;         // incomplete maps dropped after pending_map_timeout_s
  int64_t malformed_messages = 0;   // did not decode as the channel's type
  int64_t invalid_tiles = 0;        // decoded, but the tile's fields or CRC are wrong
  int64_t inconsistent_tiles = 0;   // disagrees with its map's other tiles or its layout
  int64_t assembler_full = 0;       // too many maps being received at once
  int64_t wrong_vehicle_id = 0;     // TEMPMAP_<a> carrying a tile of vehicle b
  int64_t unknown_channel = 0;      // a channel the node does not serve
  int64_t ignored_messages = 0;     // our own TEMPMAP_ACK seen on the uplink (one group)
  int64_t requests = 0;             // valid MAP_REQUESTs
  int64_t bad_requests = 0;         // MAP_REQUESTs with impossible versions or tiles
  int64_t bytes_sent = 0;           // every message handed to the downlink, bytes
  int64_t keyframe_tiles_sent = 0;  // MAP_KEYFRAME messages
  int64_t asked_tiles_sent = 0;     // of them, tiles a MAP_REQUEST asked for
  int64_t keyframe_rounds = 0;      // rounds of the rolling keyframe completed
  int64_t delta_tiles_sent = 0;     // MAP_DELTA messages (new versions and resends)
  int64_t deltas_resent = 0;        // versions resent for a MAP_REQUEST
  int64_t acks_sent = 0;            // TEMPMAP_ACK messages, any outcome
  int64_t pending_acks_sent = 0;    // of which PENDING
  int64_t merge_reports_sent = 0;
  int64_t persist_errors = 0;        // journal writes that failed: nothing acknowledged
  int64_t persist_backlog_full = 0;  // maps not kept to wait for the journal: wait for resend
  int64_t snapshot_errors = 0;       // snapshots that failed after a journaled merge
  int64_t spool_errors = 0;          // tiles that could not be kept on disk (not acknowledged)
  int64_t submit_errors = 0;         // the aggregator refused a commit (a bug): rejected
  int64_t publish_failures = 0;      // the transport refused a message
  int64_t oversize_messages = 0;     // published messages over max_message_bytes
  // Bounds per vehicle (vehicle_limits.h) and the authentication (auth/verifier.h, whose
  // counters follow these in STATUS).
  int64_t oversize_received = 0;      // received messages over limits.max_received_bytes
  int64_t throttled_tiles = 0;        // tiles of a vehicle over its tile rate: dropped
  int64_t throttled_merges = 0;       // complete maps of a vehicle over its merge rate: wait
  int64_t vehicle_maps_full = 0;      // a new map of a vehicle with too many incomplete ones
  int64_t auth_refused = 0;           // messages the verifier refused (by cause: auth_*)
  int64_t seen_free_reports = 0;      // valid CANDIDATES_FREE_<id> reports
  int64_t bad_seen_free = 0;          // reports with impossible cells or times
  int64_t candidates_dropped = 0;     // candidates dropped because a vehicle saw them free
  int64_t held_reports = 0;           // valid CANDIDATES_HELD_<id> reports
  int64_t bad_held = 0;               // reports with impossible cells or times
  int64_t candidates_held_added = 0;  // candidates added because a vehicle saw them held
  int64_t candidate_sets_sent = 0;    // MAP_CANDIDATES sets (each in one or more parts)
};

using NamedCounters = std::vector<std::pair<std::string, int64_t>>;

// Every counter with its field name, in declaration order.
NamedCounters Named(const NodeCounters& c);

}  // namespace fleetmap::aggregator::node
