// Every setting of the aggregator node, with its default and unit. The process fills them
// from its YAML file and flags (node_config.h); docs/aggregator_process.md lists them in
// this order.
#pragma once

#include <optional>
#include <string>

#include "aggregator/node/vehicle_limits.h"
#include "auth/key.h"
#include "core/codec/send_pacer.h"
#include "core/codec/temp_map_tiles.h"

namespace fleetmap::aggregator::node {

struct AggregatorNodeOptions {
  // An incomplete temporary map gets a PENDING acknowledgement (the tiles received so far)
  // at most this often, s > 0, the first this long after its first tile: its other tiles
  // usually follow in the same burst, and the vehicle resends after 1 s by default.
  double pending_ack_interval_s = 0.5;
  // The rolling keyframe sends every tile of the current map in turn, one round per this
  // (longer when the downlink's budget does not allow it), so that a vehicle that missed
  // everything catches up; the candidates go out as often. s >= 0 (0: neither).
  double keyframe_period_s = 10.0;
  // The downlink's budget (docs/channels.md): everything the node sends, paced, bytes/s > 0.
  // Multicast on Wi-Fi goes at the channel's basic rate (often 6 Mbit/s): 200 kB/s is 1.6
  // Mbit/s of it, and a 44M-cell hall's whole map (2.1 MB) in about 11 s.
  double downlink_bytes_per_s = 200000.0;
  // ... and messages/s > 0: tiles are small, and slow readers (lcm-logger) drop bursts.
  double downlink_messages_per_s = 2000.0;
  // The share of downlink_bytes_per_s the rolling keyframe may take, 0 < share <= 1: on a
  // large map its round then lasts longer than keyframe_period_s (a 40M-cell hall's 2 MB at
  // 50 kB/s: 40 s) rather than keeping the channel full with tiles nobody asked for. Tiles
  // vehicles ask for are not limited by it.
  double keyframe_share = 0.25;
  double status_period_s = 1.0;  // STATUS_aggregator period, s > 0
  // An incomplete map that received no tile for this long is dropped, s > 0. A live vehicle
  // resends at least every max_resend_s (16 s by default).
  double pending_map_timeout_s = 600.0;
  // A message the node publishes larger than this is counted (oversize_messages) and
  // logged, bytes >= 1024: one lost UDP packet loses a whole message, so they stay small.
  int max_message_bytes = 16384;
  int max_report_matches = 64;  // line pairs listed in a MERGE_REPORT at most, >= 0
  // Rejected (vehicle, sequence) remembered to answer resends with DUPLICATE, >= 1. Merged
  // ones are always remembered: the current map's history holds them.
  int max_remembered_rejections = 10000;
  // Maps whose journal write failed (a full disk), with the maps completed after them, kept
  // in arrival order and merged once the journal writes again, >= 1. Beyond, a map waits
  // unacknowledged for its vehicle's resend (and may then merge out of arrival order).
  int max_retry_maps = 256;
  // Complete maps over their vehicle's merge rate, held to merge in order once it allows,
  // >= 1 (limits.merges_per_min); beyond, a map waits for the vehicle's resend.
  int max_held_maps = 128;
  core::AssemblerOptions assembler;  // bounds on temporary maps being received
  VehicleLimitOptions limits;        // bounds per vehicle: sizes, rates, pending maps
  // The fleet key (docs/security.md): every message sent is signed as process_name, and a
  // message received counts only if its channel's owner signed it. None: unauthenticated.
  std::optional<auth::Key> fleet_key;
  // Where tiles of incomplete maps are kept once acknowledged (PENDING), so that a restarted
  // aggregator still has them: the vehicle never resends a tile it saw acknowledged. Empty:
  // memory only. The process uses <state-dir>/incoming.
  std::string spool_dir;
  // After `fleetmap-mapctl recover` (aggregator/persistence/recovery_marker.h): STATUS names the
  // recovery (recovery_id, recovered_version) until `until_s`, and the vehicles send again
  // the merged maps they hold from later versions. id 0: none.
  struct Recovery {
    int64_t id = 0;
    int64_t version = -1;
    double until_s = 0.0;  // the node's clock
  } recovery;
  // How long after a recovery STATUS asks for the lost maps, seconds (the vehicles keep
  // merged maps for outbox.retain_merged_s, a day by default).
  double recovery_request_s = 86400.0;
  std::string process_name = "aggregator";   // STATUS_<process_name>
  std::string software_version = "unknown";  // in STATUS
  core::Status Validate() const;
  // The downlink's pacing: the budget above, a tenth of a second of it (at least one message
  // of max_message_bytes) at once.
  core::PacerOptions DownlinkPacer() const;
};

}  // namespace fleetmap::aggregator::node
