#include "drivers/can/diff_drive_can_options.h"

#include <cmath>

#include "core/io/file_io.h"
#include "core/io/yaml_reader.h"

namespace fleetmap::drivers::can {
namespace {

core::Status CheckNode(const DriveNodeOptions& n, const std::string& side) {
  if (n.node_id < 1 || n.node_id > 127) {
    return core::InvalidArgument("can_odometry." + side + ".node_id must be in 1..127");
  }
  if (n.cob_id() > 0x7FF)
    return core::InvalidArgument("can_odometry." + side + ".tpdo_cob_id > 0x7FF");
  if (n.byte_offset < 0 || n.byte_offset > 4) {
    return core::InvalidArgument("can_odometry." + side + ".byte_offset must be in 0..4");
  }
  if (!std::isfinite(n.scaling) || n.scaling == 0.0) {
    return core::InvalidArgument("can_odometry." + side + ".scaling must be finite and non-zero");
  }
  return core::OkStatus();
}

core::Status ReadNode(const core::YamlReader& r, const YAML::Node& parent, const std::string& side,
                      DriveNodeOptions& n) {
  if (!parent[side]) return core::OkStatus();
  const YAML::Node node = parent[side];
  const std::string f = side + ".";
  FLEETMAP_ASSIGN_OR_RETURN(n.node_id, r.GetOr<int>(node, "node_id", f + "node_id", n.node_id));
  FLEETMAP_ASSIGN_OR_RETURN(
      n.tpdo_cob_id, r.GetOr<uint32_t>(node, "tpdo_cob_id", f + "tpdo_cob_id", n.tpdo_cob_id));
  FLEETMAP_ASSIGN_OR_RETURN(n.byte_offset,
                            r.GetOr<int>(node, "byte_offset", f + "byte_offset", n.byte_offset));
  FLEETMAP_ASSIGN_OR_RETURN(n.scaling, r.Number(node, "scaling", f + "scaling", n.scaling));
  FLEETMAP_ASSIGN_OR_RETURN(n.inverted,
                            r.GetOr<bool>(node, "inverted", f + "inverted", n.inverted));
  std::string object = n.object == DriveObject::kPosition ? "position" : "velocity";
  FLEETMAP_ASSIGN_OR_RETURN(object, r.GetOr<std::string>(node, "object", f + "object", object));
  if (object != "position" && object != "velocity") {
    return r.Error(node["object"], f + "object", "must be position or velocity");
  }
  n.object = object == "position" ? DriveObject::kPosition : DriveObject::kVelocity;
  return core::OkStatus();
}

}  // namespace

double DiffDriveCanOptions::metres_per_tick() const {
  return 2.0 * M_PI * wheel_radius_m / (ticks_per_revolution * gear_ratio);
}

core::Status DiffDriveCanOptions::Validate() const {
  if (sync_cob_id > 0x7FF) return core::InvalidArgument("can_odometry.sync_cob_id > 0x7FF");
  for (const auto& [value, name] :
       {std::pair{wheel_radius_m, "wheel_radius_m"}, std::pair{gear_ratio, "gear_ratio"},
        std::pair{ticks_per_revolution, "ticks_per_revolution"},
        std::pair{track_width_m, "track_width_m"}}) {
    if (!(std::isfinite(value) && value > 0.0)) {
      return core::InvalidArgument(std::string("can_odometry.") + name + " must be positive");
    }
  }
  FLEETMAP_RETURN_IF_ERROR(CheckNode(left, "left"));
  FLEETMAP_RETURN_IF_ERROR(CheckNode(right, "right"));
  if (left.cob_id() == right.cob_id() || left.cob_id() == sync_cob_id ||
      right.cob_id() == sync_cob_id) {
    return core::InvalidArgument("can_odometry: left, right and sync COB-IDs must differ");
  }
  return core::OkStatus();
}

core::Result<DiffDriveCanOptions> ParseDiffDriveCanOptions(const std::string& yaml_text,
                                                           const std::string& name) {
  core::Result<core::YamlReader> reader = core::YamlReader::FromString(yaml_text, name);
  if (!reader.ok()) return reader.status();
  const core::YamlReader& r = *reader;
  const YAML::Node& root = r.root();
  DiffDriveCanOptions o;
  FLEETMAP_ASSIGN_OR_RETURN(o.sync_cob_id,
                            r.GetOr<uint32_t>(root, "sync_cob_id", "sync_cob_id", o.sync_cob_id));
  FLEETMAP_ASSIGN_OR_RETURN(o.wheel_radius_m,
                            r.Number(root, "wheel_radius_m", "wheel_radius_m", o.wheel_radius_m));
  FLEETMAP_ASSIGN_OR_RETURN(o.gear_ratio, r.Number(root, "gear_ratio", "gear_ratio", o.gear_ratio));
  FLEETMAP_ASSIGN_OR_RETURN(
      o.ticks_per_revolution,
      r.Number(root, "ticks_per_revolution", "ticks_per_revolution", o.ticks_per_revolution));
  FLEETMAP_ASSIGN_OR_RETURN(o.track_width_m,
                            r.Number(root, "track_width_m", "track_width_m", o.track_width_m));
  FLEETMAP_RETURN_IF_ERROR(ReadNode(r, root, "left", o.left));
  FLEETMAP_RETURN_IF_ERROR(ReadNode(r, root, "right", o.right));
  FLEETMAP_RETURN_IF_ERROR(o.Validate().WithContext(name));
  return o;
}

core::Result<DiffDriveCanOptions> LoadDiffDriveCanOptions(const std::string& path) {
  core::Result<std::string> text = core::ReadFileBytes(path, 1 << 20);
  if (!text.ok()) return text.status();
  return ParseDiffDriveCanOptions(*text, path);
}

}  // namespace fleetmap::drivers::can
