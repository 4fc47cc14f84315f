#include "aggregator/node/messages.h"

#include <algorithm>
#include <limits>

#include "lcmtypes/transport_convert.h"

namespace fleetmap::aggregator::node {

int32_t WireVersion(uint64_t version) {
  return static_cast<int32_t>(
      std::min<uint64_t>(version, static_cast<uint64_t>(std::numeric_limits<int32_t>::max())));
}

fleetmap::tempmap_ack_t AckMessage(const AckFields& f, int64_t utime) {
  fleetmap::tempmap_ack_t m;
  m.utime = utime;
  m.vehicle_id = f.key.vehicle_id;
  m.tempmap_seq = f.key.sequence;
  m.tile_count = f.tile_count;
  for (int32_t i : f.received) m.received_tiles.push_back(static_cast<int16_t>(i));
  m.num_received = static_cast<int32_t>(m.received_tiles.size());
  m.outcome = f.outcome;
  m.reason = f.reason;
  m.map_version = WireVersion(f.map_version);
  return m;
}

fleetmap::merge_report_t ReportMessage(const MergeReport& r, const core::Pose2& anchor,
                                       int max_matches, int64_t utime) {
  fleetmap::merge_report_t m;
  m.utime = utime;
  m.vehicle_id = r.vehicle_id;
  m.tempmap_seq = r.tempmap_sequence;
  m.accepted = r.accepted;
  m.reason = r.accepted ? "" : r.reason_text;
  const core::Pose2 placed = r.alignment.correction * anchor;
  m.dx_m = placed.x_m - anchor.x_m;
  m.dy_m = placed.y_m - anchor.y_m;
  m.dtheta_rad = core::NormalizeAngle(placed.theta_rad - anchor.theta_rad);
  m.score = r.confidence.score;
  for (const LineReportRow& row : r.lines) {
    if (static_cast<int>(m.matches.size()) >= max_matches) break;
    fleetmap::line_match_t match;
    match.temp_line_id = row.temp_line_id;
    match.static_line_id = row.static_line_id;
    match.distance_diff_px = row.distance_diff_px;
    match.angle_diff_deg = row.angle_diff_deg;
    m.matches.push_back(match);
  }
  m.num_matches = static_cast<int32_t>(m.matches.size());
  m.cells_added = r.cells_added;
  m.cells_removed = r.cells_removed;
  m.new_version = WireVersion(r.version);
  return m;
}

fleetmap::status_t StatusMessage(const StatusFields& f, int64_t utime) {
  fleetmap::status_t m;
  m.utime = utime;
  m.process = f.process;
  m.software_version = f.software_version;
  m.map_version = WireVersion(f.map_version);
  m.state = f.state;
  m.authenticated = f.authenticated;
  for (const auto& [name, value] : f.counters) {
    m.counter_names.push_back(name);
    m.counter_values.push_back(value);
  }
  m.num_counters = static_cast<int32_t>(m.counter_names.size());
  return m;
}

std::vector<fleetmap::map_delta_t> DeltaMessages(const MapDelta& delta, int64_t utime) {
  std::vector<fleetmap::map_delta_t> out;
  core::DeltaTile d;
  d.base_version = WireVersion(delta.from_version);
  d.count = static_cast<int32_t>(delta.tiles.size());
  if (delta.tiles.empty()) {
    out.push_back(lcmtypes::ToMessage(d, utime));
    return out;
  }
  for (size_t i = 0; i < delta.tiles.size(); ++i) {
    d.index = static_cast<int32_t>(i);
    d.tile = delta.tiles[i].index;
    d.frame = delta.tiles[i].frame;
    out.push_back(lcmtypes::ToMessage(d, utime));
  }
  return out;
}

std::vector<fleetmap::map_keyframe_t> KeyframeMessages(const CurrentMapStore& store,
                                                       const core::TileOptions& tiles,
                                                       const std::vector<int32_t>* only,
                                                       int64_t utime) {
  const core::TileLayout layout(store.current_map().geometry(), tiles.tile_size_cells);
  std::vector<int32_t> indices;
  if (only) {
    for (int32_t i : *only)
      if (i >= 0 && i < layout.num_tiles()) indices.push_back(i);
  } else {
    for (int32_t i = 0; i < layout.num_tiles(); ++i) indices.push_back(i);
  }
  core::KeyframeTile k;
  k.version = WireVersion(store.version());
  k.geometry = store.current_map().geometry();
  k.tile_size_cells = tiles.tile_size_cells;
  k.count = layout.num_tiles();
  std::vector<fleetmap::map_keyframe_t> out;
  for (int32_t i : indices) {
    k.index = i;
    k.tile = layout.FromLinear(i);
    k.frame = core::EncodeWindow(store.current_map(), layout.Window(k.tile), tiles.codec);
    out.push_back(lcmtypes::ToMessage(k, utime));
  }
  return out;
}

}  // namespace fleetmap::aggregator::node
