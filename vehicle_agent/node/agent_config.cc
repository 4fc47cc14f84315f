#include "vehicle_agent/node/agent_config.h"

#include <cmath>

#include "core/io/file_io.h"
#include "core/io/yaml_reader.h"
#include "lcmtypes/convert.h"
#include "vehicle_agent/node/config_reading.h"
#include "vehicle_agent/node/input_config.h"
#include "vehicle_agent/node/pipeline_config.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using core::YamlReader;

// [x_m, y_m, theta_rad].
core::Result<core::Pose2> ReadPose(const YamlReader& r, const YAML::Node& node,
                                   const std::string& field) {
  auto v = r.Numbers(node, field, 3);
  if (!v.ok()) return v.status();
  return core::Pose2((*v)[0], (*v)[1], (*v)[2]);
}

core::Status ReadInitialPose(const YamlReader& r, const YAML::Node& root, AgentConfig& c) {
  if (!root["initial_pose"]) return core::OkStatus();
  const YAML::Node n = root["initial_pose"];
  if (n.IsScalar()) {
    c.initial_pose_explicit = true;
    if (n.Scalar() == "global") {
      c.node.initial_pose = InitialPoseSource::kGlobal;
    } else if (n.Scalar() == "external") {
      c.node.initial_pose = InitialPoseSource::kFirstExternal;
    } else {
      return r.Error(n, "initial_pose", "must be global, external or {x_m, y_m, theta_rad, ...}");
    }
    return core::OkStatus();
  }
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, n, "initial_pose",
                                     {"x_m", "y_m", "theta_rad", "sigma_xy_m", "sigma_theta_rad"}));
  LocalizerOptions& l = c.node.pipeline.localizer;
  core::Pose2& p = l.initial_pose_in_map;
  FLEETMAP_ASSIGN_OR_RETURN(p.x_m, r.Number(n, "x_m", "initial_pose.x_m"));
  FLEETMAP_ASSIGN_OR_RETURN(p.y_m, r.Number(n, "y_m", "initial_pose.y_m"));
  FLEETMAP_ASSIGN_OR_RETURN(p.theta_rad, r.Number(n, "theta_rad", "initial_pose.theta_rad"));
  FLEETMAP_READ_NUMBER(r, n, "sigma_xy_m", "initial_pose.", l.initial_sigma_xy_m);
  FLEETMAP_READ_NUMBER(r, n, "sigma_theta_rad", "initial_pose.", l.initial_sigma_theta_rad);
  c.node.initial_pose = InitialPoseSource::kGiven;
  c.initial_pose_explicit = true;
  return core::OkStatus();
}

core::Status ReadOutbox(const YamlReader& r, const YAML::Node& n, OutboxOptions& o) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, n, "outbox",
                                     {"first_resend_s", "max_resend_s", "max_pending_maps",
                                      "tile_size_cells", "retain_merged_s", "max_retained_bytes"}));
  FLEETMAP_READ_NUMBER(r, n, "first_resend_s", "outbox.", o.first_resend_s);
  FLEETMAP_READ_NUMBER(r, n, "max_resend_s", "outbox.", o.max_resend_s);
  FLEETMAP_READ_AS(r, int, n, "max_pending_maps", "outbox.", o.max_pending_maps);
  FLEETMAP_READ_AS(r, int, n, "tile_size_cells", "outbox.", o.tile_size_cells);
  FLEETMAP_READ_NUMBER(r, n, "retain_merged_s", "outbox.", o.retain_merged_s);
  FLEETMAP_READ_AS(r, int64_t, n, "max_retained_bytes", "outbox.", o.max_retained_bytes);
  return core::OkStatus();
}

core::Status ReadLastPose(const YamlReader& r, const YAML::Node& n, KeptPoseOptions& o) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "last_pose", {"period_s", "same_odometry_m", "same_odometry_rad"}));
  FLEETMAP_READ_NUMBER(r, n, "period_s", "last_pose.", o.period_s);
  FLEETMAP_READ_NUMBER(r, n, "same_odometry_m", "last_pose.", o.same_odometry_m);
  FLEETMAP_READ_NUMBER(r, n, "same_odometry_rad", "last_pose.", o.same_odometry_rad);
  return core::OkStatus();
}

core::Status ReadRates(const YamlReader& r, const YAML::Node& n, AgentConfig& c) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "rates",
                {"status_period_s", "map_request_period_s", "max_queued_scans", "loop_wait_s",
                 "shutdown_drain_s", "uplink_tiles_per_s", "uplink_burst_tiles"}));
  FLEETMAP_READ_NUMBER(r, n, "status_period_s", "rates.", c.node.status_period_s);
  FLEETMAP_READ_NUMBER(r, n, "map_request_period_s", "rates.", c.node.map.request_period_s);
  FLEETMAP_READ_AS(r, int, n, "max_queued_scans", "rates.", c.node.queue.max_queued_scans);
  FLEETMAP_READ_NUMBER(r, n, "loop_wait_s", "rates.", c.loop_wait_s);
  FLEETMAP_READ_NUMBER(r, n, "shutdown_drain_s", "rates.", c.shutdown_drain_s);
  FLEETMAP_READ_NUMBER(r, n, "uplink_tiles_per_s", "rates.", c.node.uplink_pacer.rate_per_s);
  FLEETMAP_READ_NUMBER(r, n, "uplink_burst_tiles", "rates.", c.node.uplink_pacer.burst);
  return core::OkStatus();
}

core::Status ReadLinks(const YamlReader& r, const YAML::Node& root, AgentConfig& c) {
  if (const YAML::Node u = Section(root, "urls")) {
    FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, u, "urls", {"sensor", "uplink", "downlink"}));
    FLEETMAP_READ_AS(r, std::string, u, "sensor", "urls.", c.urls.sensor);
    FLEETMAP_READ_AS(r, std::string, u, "uplink", "urls.", c.urls.uplink);
    FLEETMAP_READ_AS(r, std::string, u, "downlink", "urls.", c.urls.downlink);
  }
  if (const YAML::Node m = Section(root, "map_updates")) {
    FLEETMAP_RETURN_IF_ERROR(CheckKeys(
        r, m, "map_updates", {"tile_size_cells", "max_buffered_versions", "max_request_tiles"}));
    FLEETMAP_READ_AS(r, int, m, "tile_size_cells", "map_updates.", c.node.map.tile_size_cells);
    FLEETMAP_READ_AS(r, int, m, "max_buffered_versions", "map_updates.",
                     c.node.map.max_buffered_versions);
    FLEETMAP_READ_AS(r, int, m, "max_request_tiles", "map_updates.", c.node.map.max_request_tiles);
  }
  return ReadChoice<Link>(r, root, "pose_link", "pose_link",
                          {{"uplink", Link::kUplink}, {"sensor", Link::kSensor}}, c.node.pose_link);
}

// A file name relative to the configuration's folder; empty stays empty.
core::Status ReadPath(const YamlReader& r, const YAML::Node& root, const char* key,
                      std::string& out) {
  FLEETMAP_ASSIGN_OR_RETURN(out, r.GetOr<std::string>(root, key, key, out));
  if (!out.empty()) out = r.Resolve(out);
  return core::OkStatus();
}

}  // namespace

AgentConfig::AgentConfig() {
  urls = {lcmtypes::kDefaultSensorUrl, lcmtypes::kDefaultUplinkUrl, lcmtypes::kDefaultDownlinkUrl};
  // An agent answers quickly when its scanner is away: the loop waits for connects.
  sick.client.connect_timeout_s = 0.5;
  // ... and must come back within a second of the scanner's return (docs/reliability.md): the
  // scanner sits on the vehicle's own Ethernet, so trying twice a second costs nothing.
  sick.client.reconnect_backoff_max_s = 0.5;
  node.initial_pose = InitialPoseSource::kGlobal;
  node.software_version = FLEETMAP_VERSION;
}

void AgentConfig::FinishDefaults() {
  if (!initial_pose_explicit) {
    node.initial_pose =
        node.use_external_pose ? InitialPoseSource::kFirstExternal : InitialPoseSource::kGlobal;
  }
  node.scans_from_lcm = scan_source == ScanSource::kLcm;
  node.odometry_from_lcm = odom_source == OdomSource::kLcm;
}

core::Status AgentConfig::Validate() const {
  if (node.pipeline.vehicle_id.empty() || node.pipeline.vehicle_id == "vehicle")
    return core::InvalidArgument("vehicle_id is required (config key vehicle_id or --vehicle-id)");
  FLEETMAP_RETURN_IF_ERROR(node.Validate());
  if (node.scans_from_lcm != (scan_source == ScanSource::kLcm) ||
      node.odometry_from_lcm != (odom_source == OdomSource::kLcm))
    return core::InvalidArgument("internal: inputs and node options disagree");
  if (scan_source == ScanSource::kSick) FLEETMAP_RETURN_IF_ERROR(sick.Validate());
  if (odom_source == OdomSource::kCan) FLEETMAP_RETURN_IF_ERROR(can.Validate());
  if (!(loop_wait_s > 0.0 && loop_wait_s <= 0.1))
    return core::InvalidArgument("rates.loop_wait_s must be in (0, 0.1]");
  if (!(shutdown_drain_s >= 0.0 && shutdown_drain_s <= 60.0))
    return core::InvalidArgument("rates.shutdown_drain_s must be in [0, 60]");
  if (!(duration_s >= 0.0 && std::isfinite(duration_s)))
    return core::InvalidArgument("--duration must be >= 0");
  for (const std::string* url : {&urls.sensor, &urls.uplink, &urls.downlink})
    if (url->empty()) return core::InvalidArgument("urls: a link URL is empty");
  return core::OkStatus();
}

core::Result<AgentConfig> ParseAgentConfig(const std::string& yaml_text, const std::string& path) {
  auto reader = YamlReader::FromString(yaml_text, path);
  if (!reader.ok()) return reader.status();
  const YamlReader& r = *reader;
  const YAML::Node& root = r.root();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, root, "",
                {"vehicle_id", "map", "state_dir", "final_map", "key_file", "scanner_mount",
                 "initial_pose", "urls", "inputs", "localization", "divergence", "builder",
                 "candidate_watch", "outbox", "map_updates", "rates", "pose_link", "last_pose"}));
  AgentConfig c;
  AgentPipelineOptions& p = c.node.pipeline;
  FLEETMAP_ASSIGN_OR_RETURN(p.vehicle_id,
                            r.GetOr<std::string>(root, "vehicle_id", "vehicle_id", p.vehicle_id));
  FLEETMAP_RETURN_IF_ERROR(ReadPath(r, root, "map", c.map_yaml));
  FLEETMAP_RETURN_IF_ERROR(ReadPath(r, root, "state_dir", c.node.outbox.state_dir));
  FLEETMAP_RETURN_IF_ERROR(ReadPath(r, root, "final_map", c.final_map_yaml));
  FLEETMAP_RETURN_IF_ERROR(ReadPath(r, root, "key_file", c.key_file));
  if (root["scanner_mount"])
    FLEETMAP_ASSIGN_OR_RETURN(p.scanner_in_base,
                              ReadPose(r, root["scanner_mount"], "scanner_mount"));
  FLEETMAP_RETURN_IF_ERROR(ReadInitialPose(r, root, c));
  FLEETMAP_RETURN_IF_ERROR(ReadInputs(r, Section(root, "inputs"), c));
  FLEETMAP_RETURN_IF_ERROR(ReadLocalization(r, Section(root, "localization"), p.localizer));
  FLEETMAP_RETURN_IF_ERROR(ReadDivergence(r, Section(root, "divergence"), p.divergence));
  FLEETMAP_RETURN_IF_ERROR(ReadBuilder(r, Section(root, "builder"), p.builder));
  FLEETMAP_RETURN_IF_ERROR(ReadCandidateWatch(r, Section(root, "candidate_watch"), p));
  FLEETMAP_RETURN_IF_ERROR(ReadOutbox(r, Section(root, "outbox"), c.node.outbox));
  FLEETMAP_RETURN_IF_ERROR(ReadLastPose(r, Section(root, "last_pose"), c.node.last_pose));
  FLEETMAP_RETURN_IF_ERROR(ReadRates(r, Section(root, "rates"), c));
  FLEETMAP_RETURN_IF_ERROR(ReadLinks(r, root, c));
  c.FinishDefaults();
  return c;
}

core::Result<AgentConfig> LoadAgentConfig(const std::string& path) {
  core::Result<std::string> text = core::ReadFileBytes(path, 1 << 20);
  if (!text.ok()) return text.status();
  return ParseAgentConfig(*text, path);
}

}  // namespace fleetmap::vehicle_agent::node
