#include "aggregator/node/node_config.h"

#include <set>

#include "core/io/file_io.h"
#include "core/io/yaml_reader.h"
#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {
namespace {

using core::YamlReader;

// A typo in a key must not silently leave a default in place.
core::Status OnlyKeys(const YamlReader& r, const YAML::Node& node, const std::string& section,
                      const std::set<std::string>& allowed) {
  if (!node) return core::OkStatus();
  if (!node.IsMap()) return r.Error(node, section, "must be a map of keys");
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    if (!allowed.count(key)) {
      return r.Error(item.first, (section.empty() ? "" : section + ".") + key, "unknown key");
    }
  }
  return core::OkStatus();
}

template <typename T>
core::Status Read(const YamlReader& r, const YAML::Node& parent, const std::string& section,
                  const std::string& key, T& value) {
  const std::string field = section + "." + key;
  if constexpr (std::is_floating_point_v<T>) {
    FLEETMAP_ASSIGN_OR_RETURN(value, r.Number(parent, key, field, static_cast<double>(value)));
  } else {
    FLEETMAP_ASSIGN_OR_RETURN(value, r.GetOr<T>(parent, key, field, value));
  }
  return core::OkStatus();
}

core::Status ReadNode(const YamlReader& r, const YAML::Node& n, AggregatorNodeOptions& o) {
  FLEETMAP_RETURN_IF_ERROR(OnlyKeys(
      r, n, "node",
      {"pending_ack_interval_s", "keyframe_period_s", "downlink_bytes_per_s",
       "downlink_messages_per_s", "keyframe_share", "status_period_s", "pending_map_timeout_s",
       "max_message_bytes", "max_report_matches", "max_remembered_rejections", "max_retry_maps",
       "max_held_maps", "recovery_request_s"}));
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "pending_ack_interval_s", o.pending_ack_interval_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "keyframe_period_s", o.keyframe_period_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "downlink_bytes_per_s", o.downlink_bytes_per_s));
  FLEETMAP_RETURN_IF_ERROR(
      Read(r, n, "node", "downlink_messages_per_s", o.downlink_messages_per_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "keyframe_share", o.keyframe_share));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "status_period_s", o.status_period_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "pending_map_timeout_s", o.pending_map_timeout_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "max_message_bytes", o.max_message_bytes));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "max_report_matches", o.max_report_matches));
  FLEETMAP_RETURN_IF_ERROR(
      Read(r, n, "node", "max_remembered_rejections", o.max_remembered_rejections));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "max_retry_maps", o.max_retry_maps));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "node", "recovery_request_s", o.recovery_request_s));
  return Read(r, n, "node", "max_held_maps", o.max_held_maps);
}

core::Status ReadAssembler(const YamlReader& r, const YAML::Node& n, core::AssemblerOptions& o) {
  FLEETMAP_RETURN_IF_ERROR(OnlyKeys(
      r, n, "assembler", {"tile_size_cells", "max_pending_maps", "max_map_cells", "max_tiles"}));
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "assembler", "tile_size_cells", o.tile_size_cells));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "assembler", "max_pending_maps", o.max_pending_maps));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "assembler", "max_map_cells", o.max_map_cells));
  return Read(r, n, "assembler", "max_tiles", o.max_tiles);
}

core::Status ReadLimits(const YamlReader& r, const YAML::Node& n, VehicleLimitOptions& o) {
  FLEETMAP_RETURN_IF_ERROR(
      OnlyKeys(r, n, "limits",
               {"max_received_bytes", "max_pending_maps_per_vehicle", "tiles_per_s", "tile_burst",
                "merges_per_min", "merge_burst", "max_replay_speed", "max_vehicles"}));
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "limits", "max_received_bytes", o.max_received_bytes));
  FLEETMAP_RETURN_IF_ERROR(
      Read(r, n, "limits", "max_pending_maps_per_vehicle", o.max_pending_maps_per_vehicle));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "limits", "tiles_per_s", o.tiles_per_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "limits", "tile_burst", o.tile_burst));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "limits", "merges_per_min", o.merges_per_min));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "limits", "merge_burst", o.merge_burst));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, "limits", "max_replay_speed", o.max_replay_speed));
  return Read(r, n, "limits", "max_vehicles", o.max_vehicles);
}

// Keys of earlier versions, in cells, and what replaced them: refused with the new name, so
// that an old file does not silently mean another distance at another resolution.
core::Status RefuseCellKeys(const YamlReader& r, const YAML::Node& n, const std::string& s) {
  for (const char* old : {"static_clearance", "removal_clearance", "confirm_radius"}) {
    const std::string key = std::string(old) + "_cells";
    if (n && n.IsMap() && n[key])
      return r.Error(n[key], s + "." + key,
                     std::string("is now ") + old + "_m, in metres (2 cells at 0.05 m are 0.10)");
  }
  return core::OkStatus();
}

core::Status ReadMerge(const YamlReader& r, const YAML::Node& n, MergeOptions& o) {
  const std::string s = "aggregator.merge";
  FLEETMAP_RETURN_IF_ERROR(RefuseCellKeys(r, n, s));
  FLEETMAP_RETURN_IF_ERROR(
      OnlyKeys(r, n, s,
               {"add_min_log_odds", "remove_max_log_odds", "static_clearance_m",
                "min_occupied_neighbours", "removal_clearance_m", "confirmations",
                "confirm_radius_m", "confirm_min_gap_s", "confirm_max_gap_s", "confirm_by_watch",
                "watch_join_s", "wall_offset_window_m", "held_wall_clearance_m"}));
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "add_min_log_odds", o.add_min_log_odds));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "remove_max_log_odds", o.remove_max_log_odds));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "static_clearance_m", o.static_clearance_m));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "wall_offset_window_m", o.wall_offset_window_m));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "held_wall_clearance_m", o.held_wall_clearance_m));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "min_occupied_neighbours", o.min_occupied_neighbours));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "removal_clearance_m", o.removal_clearance_m));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "confirmations", o.confirmations));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "confirm_radius_m", o.confirm_radius_m));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "confirm_min_gap_s", o.confirm_min_gap_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "confirm_max_gap_s", o.confirm_max_gap_s));
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "confirm_by_watch", o.confirm_by_watch));
  return Read(r, n, s, "watch_join_s", o.watch_join_s);
}

core::Status ReadCellAlignment(const YamlReader& r, const YAML::Node& n, CellAlignmentOptions& o) {
  const std::string s = "aggregator.cell_alignment";
  FLEETMAP_RETURN_IF_ERROR(
      OnlyKeys(r, n, s, {"use", "range_m", "range_deg", "lines_min_relative_score"}));
  if (!n) return core::OkStatus();
  if (n["use"]) {
    std::string use = CellAlignmentUseName(o.use);
    FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "use", use));
    auto parsed = ParseCellAlignmentUse(use);
    if (!parsed.ok()) return r.Error(n["use"], s + ".use", parsed.status().message());
    o.use = *parsed;
  }
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "range_m", o.range_m));
  double range_deg = o.range_rad * 180 / M_PI;
  FLEETMAP_RETURN_IF_ERROR(Read(r, n, s, "range_deg", range_deg));
  o.range_rad = range_deg * M_PI / 180;
  return Read(r, n, s, "lines_min_relative_score", o.lines_min_relative_score);
}

core::Status ReadAggregator(const YamlReader& r, const YAML::Node& n, AggregatorOptions& o) {
  FLEETMAP_RETURN_IF_ERROR(
      OnlyKeys(r, n, "aggregator", {"merge", "cell_alignment", "store", "persistence"}));
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(ReadMerge(r, n["merge"], o.merge));
  FLEETMAP_RETURN_IF_ERROR(ReadCellAlignment(r, n["cell_alignment"], o.cell_alignment));
  const YAML::Node store = n["store"];
  FLEETMAP_RETURN_IF_ERROR(
      OnlyKeys(r, store, "aggregator.store", {"retained_deltas", "tile_size_cells"}));
  if (store) {
    FLEETMAP_RETURN_IF_ERROR(
        Read(r, store, "aggregator.store", "retained_deltas", o.store.retained_deltas));
    FLEETMAP_RETURN_IF_ERROR(
        Read(r, store, "aggregator.store", "tile_size_cells", o.store.tiles.tile_size_cells));
  }
  const YAML::Node persistence = n["persistence"];
  FLEETMAP_RETURN_IF_ERROR(
      OnlyKeys(r, persistence, "aggregator.persistence", {"snapshot_every_merges"}));
  if (persistence) {
    FLEETMAP_RETURN_IF_ERROR(Read(r, persistence, "aggregator.persistence", "snapshot_every_merges",
                                  o.persistence.snapshot_every_merges));
  }
  return core::OkStatus();
}

}  // namespace

AggregatorProcessConfig DefaultProcessConfig() {
  AggregatorProcessConfig c;
  c.uplink_url = lcmtypes::kDefaultUplinkUrl;
  c.downlink_url = lcmtypes::kDefaultDownlinkUrl;
  return c;
}

core::Status AggregatorProcessConfig::Validate() const {
  if (uplink_url.empty() || downlink_url.empty())
    return core::InvalidArgument("uplink_url and downlink_url must not be empty");
  FLEETMAP_RETURN_IF_ERROR(node.Validate());
  return aggregator.Validate().WithContext("aggregator");
}

core::Result<AggregatorProcessConfig> ParseProcessConfig(const std::string& yaml_text,
                                                         const std::string& name) {
  auto reader = YamlReader::FromString(yaml_text, name);
  if (!reader.ok()) return reader.status();
  const YamlReader& r = *reader;
  const YAML::Node& root = r.root();
  FLEETMAP_RETURN_IF_ERROR(OnlyKeys(r, root, "",
                                    {"uplink_url", "downlink_url", "state_dir", "key_file", "node",
                                     "assembler", "limits", "aggregator"}));
  AggregatorProcessConfig c = DefaultProcessConfig();
  FLEETMAP_ASSIGN_OR_RETURN(c.uplink_url,
                            r.GetOr<std::string>(root, "uplink_url", "uplink_url", c.uplink_url));
  FLEETMAP_ASSIGN_OR_RETURN(
      c.downlink_url, r.GetOr<std::string>(root, "downlink_url", "downlink_url", c.downlink_url));
  FLEETMAP_ASSIGN_OR_RETURN(c.state_dir,
                            r.GetOr<std::string>(root, "state_dir", "state_dir", c.state_dir));
  if (!c.state_dir.empty()) c.state_dir = r.Resolve(c.state_dir);
  FLEETMAP_ASSIGN_OR_RETURN(c.key_file,
                            r.GetOr<std::string>(root, "key_file", "key_file", c.key_file));
  if (!c.key_file.empty()) c.key_file = r.Resolve(c.key_file);
  FLEETMAP_RETURN_IF_ERROR(ReadLimits(r, root["limits"], c.node.limits));
  FLEETMAP_RETURN_IF_ERROR(ReadNode(r, root["node"], c.node));
  FLEETMAP_RETURN_IF_ERROR(ReadAssembler(r, root["assembler"], c.node.assembler));
  FLEETMAP_RETURN_IF_ERROR(ReadAggregator(r, root["aggregator"], c.aggregator));
  FLEETMAP_RETURN_IF_ERROR(c.Validate().WithContext(name));
  return c;
}

core::Result<AggregatorProcessConfig> LoadProcessConfig(const std::string& path) {
  auto text = core::ReadFileBytes(path, 1 << 20);
  if (!text.ok()) return text.status().WithContext(path);
  return ParseProcessConfig(*text, path);
}

}  // namespace fleetmap::aggregator::node
