// The LCM messages the aggregator node sends, built from the aggregator's results. Every map
// travels as tiles of a few KB (lcmtypes/transport_convert.h), so each message is small and
// useful alone.
#pragma once

#include <string>
#include <vector>

#include "aggregator/aggregator.h"
#include "aggregator/node/map_key.h"
#include "aggregator/node/node_counters.h"
#include "fleetmap/map_delta_t.hpp"
#include "fleetmap/map_keyframe_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"

namespace fleetmap::aggregator::node {

// Map versions are uint64 in the store and int32 on the wire.
int32_t WireVersion(uint64_t version);

struct AckFields {
  MapKey key;
  int32_t tile_count = 0;
  std::vector<int32_t> received;  // tile indices, ascending
  int8_t outcome = fleetmap::tempmap_ack_t::PENDING;
  std::string reason;  // REJECTED only
  uint64_t map_version = 0;
};
fleetmap::tempmap_ack_t AckMessage(const AckFields& fields, int64_t utime);

// The correction as the anchor's move: the anchor was placed at correction * anchor, so
// dx_m, dy_m and dtheta_rad are that pose minus the anchor, in the static map frame. A
// rejected map reports the correction that was computed and refused. At most max_matches
// line pairs are listed.
fleetmap::merge_report_t ReportMessage(const MergeReport& report, const core::Pose2& anchor_in_map,
                                       int max_matches, int64_t utime);

struct StatusFields {
  std::string process;
  std::string software_version;
  uint64_t map_version = 0;
  std::string state;
  bool authenticated = false;  // a fleet key is configured: peers are authenticated
  NamedCounters counters;
};
fleetmap::status_t StatusMessage(const StatusFields& fields, int64_t utime);

// One MAP_DELTA per tile of `delta` (from_version -> from_version + 1); a version that
// changed no cell is one message with tile_count 0, so that vehicles still advance.
std::vector<fleetmap::map_delta_t> DeltaMessages(const MapDelta& delta, int64_t utime);

// MAP_KEYFRAME messages of the store's current map: every tile, or only `tiles` (linear
// indices of the store's layout; out-of-range ones are skipped).
std::vector<fleetmap::map_keyframe_t> KeyframeMessages(const CurrentMapStore& store,
                                                       const core::TileOptions& tiles,
                                                       const std::vector<int32_t>* only,
                                                       int64_t utime);

}  // namespace fleetmap::aggregator::node
