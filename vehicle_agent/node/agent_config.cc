#include "vehicle_agent/node/agent_config.h"

#include <cmath>
#include <initializer_list>

#include "core/file_io.h"
#include "core/yaml_reader.h"
#include "lcmtypes/convert.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using core::YamlReader;

// Refuses keys outside `known`, naming the key, its line and the keys that exist.
core::Status CheckKeys(const YamlReader& r, const YAML::Node& node, const std::string& field,
                       std::initializer_list<const char*> known) {
  if (!node.IsMap()) return r.Error(node, field, "must be a map");
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = it->first.IsScalar() ? it->first.Scalar() : "?";
    bool ok = false;
    std::string list;
    for (const char* k : known) {
      ok |= key == k;
      list += (list.empty() ? "" : ", ") + std::string(k);
    }
    if (!ok)
      return r.Error(it->first, field.empty() ? key : field + "." + key,
                     "unknown key (known: " + list + ")");
  }
  return core::OkStatus();
}

// An optional sub-map: absent gives an undefined node the readers skip.
YAML::Node Section(const YAML::Node& parent, const char* key) {
  return parent[key] ? parent[key] : YAML::Node(YAML::NodeType::Undefined);
}

// [x_m, y_m, theta_rad].
core::Result<core::Pose2> ReadPose(const YamlReader& r, const YAML::Node& node,
                                   const std::string& field) {
  auto v = r.Numbers(node, field, 3);
  if (!v.ok()) return v.status();
  return core::Pose2((*v)[0], (*v)[1], (*v)[2]);
}

// One word out of a few.
template <typename Enum>
core::Status ReadChoice(const YamlReader& r, const YAML::Node& node, const char* key,
                        const std::string& field,
                        std::initializer_list<std::pair<const char*, Enum>> choices, Enum& out) {
  if (!node[key]) return core::OkStatus();
  auto word = r.Get<std::string>(node, key, field);
  if (!word.ok()) return word.status();
  std::string list;
  for (const auto& [name, value] : choices) {
    if (*word == name) {
      out = value;
      return core::OkStatus();
    }
    list += (list.empty() ? "" : ", ") + std::string(name);
  }
  return r.Error(node[key], field, "must be one of " + list);
}

#define READ_NUMBER(node, key, prefix, target) \
  FLEETMAP_ASSIGN_OR_RETURN(target, r.Number(node, key, prefix key, target))
#define READ_AS(type, node, key, prefix, target) \
  FLEETMAP_ASSIGN_OR_RETURN(target, r.GetOr<type>(node, key, prefix key, target))

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
  READ_NUMBER(n, "sigma_xy_m", "initial_pose.", l.initial_sigma_xy_m);
  READ_NUMBER(n, "sigma_theta_rad", "initial_pose.", l.initial_sigma_theta_rad);
  c.node.initial_pose = InitialPoseSource::kGiven;
  c.initial_pose_explicit = true;
  return core::OkStatus();
}

core::Status ReadSick(const YamlReader& r, const YAML::Node& n, SickInputOptions& s) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(
      r, n, "inputs.sick",
      {"host", "port", "protocol", "connect_timeout_s", "first_scan_timeout_s", "silence_timeout_s",
       "reconnect_backoff_initial_s", "reconnect_backoff_max_s", "login", "start_measurement",
       "streaming", "range_min_m", "range_max_m", "range_channel", "intensity_channel"}));
  drivers::sick::ScannerClientOptions& o = s.client;
  READ_AS(std::string, n, "host", "inputs.sick.", o.host);
  READ_AS(int, n, "port", "inputs.sick.", o.port);
  if (n["protocol"]) {
    auto word = r.Get<std::string>(n, "protocol", "inputs.sick.protocol");
    if (!word.ok()) return word.status();
    auto protocol = drivers::sick::ParseColaProtocol(*word);
    if (!protocol.ok())
      return r.Error(n["protocol"], "inputs.sick.protocol", protocol.status().message());
    o.protocol = *protocol;
  }
  READ_NUMBER(n, "connect_timeout_s", "inputs.sick.", o.connect_timeout_s);
  READ_NUMBER(n, "first_scan_timeout_s", "inputs.sick.", o.first_scan_timeout_s);
  READ_NUMBER(n, "silence_timeout_s", "inputs.sick.", o.silence_timeout_s);
  READ_NUMBER(n, "reconnect_backoff_initial_s", "inputs.sick.", o.reconnect_backoff_initial_s);
  READ_NUMBER(n, "reconnect_backoff_max_s", "inputs.sick.", o.reconnect_backoff_max_s);
  READ_AS(bool, n, "login", "inputs.sick.", o.login);
  READ_AS(bool, n, "start_measurement", "inputs.sick.", o.start_measurement);
  READ_AS(bool, n, "streaming", "inputs.sick.", o.streaming);
  READ_NUMBER(n, "range_min_m", "inputs.sick.", s.conversion.range_min_m);
  READ_NUMBER(n, "range_max_m", "inputs.sick.", s.conversion.range_max_m);
  READ_AS(std::string, n, "range_channel", "inputs.sick.", s.conversion.range_channel);
  READ_AS(std::string, n, "intensity_channel", "inputs.sick.", s.conversion.intensity_channel);
  return core::OkStatus();
}

core::Status ReadCan(const YamlReader& r, const YAML::Node& n, CanInputOptions& c) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, n, "inputs.can", {"interface", "mapping", "mapping_file"}));
  READ_AS(std::string, n, "interface", "inputs.can.", c.socket.interface);
  if (n["mapping"] && n["mapping_file"])
    return r.Error(n, "inputs.can", "give mapping or mapping_file, not both");
  if (n["mapping"]) {
    auto parsed = drivers::can::ParseDiffDriveCanOptions(YAML::Dump(n["mapping"]),
                                                         r.path() + ": inputs.can.mapping");
    if (!parsed.ok()) return parsed.status();
    c.odometry = *parsed;
  } else if (n["mapping_file"]) {
    auto file = r.Get<std::string>(n, "mapping_file", "inputs.can.mapping_file");
    if (!file.ok()) return file.status();
    auto parsed = drivers::can::LoadDiffDriveCanOptions(r.Resolve(*file));
    if (!parsed.ok()) return parsed.status();
    c.odometry = *parsed;
  }
  return core::OkStatus();
}

core::Status ReadInputs(const YamlReader& r, const YAML::Node& n, AgentConfig& c) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(
      r, n, "inputs",
      {"scan_source", "odom_source", "external_pose", "external_pose_mode", "sick", "can"}));
  FLEETMAP_RETURN_IF_ERROR(ReadChoice<ScanSource>(
      r, n, "scan_source", "inputs.scan_source",
      {{"lcm", ScanSource::kLcm}, {"sick", ScanSource::kSick}}, c.scan_source));
  FLEETMAP_RETURN_IF_ERROR(ReadChoice<OdomSource>(
      r, n, "odom_source", "inputs.odom_source",
      {{"lcm", OdomSource::kLcm}, {"can", OdomSource::kCan}, {"none", OdomSource::kNone}},
      c.odom_source));
  READ_AS(bool, n, "external_pose", "inputs.", c.node.use_external_pose);
  FLEETMAP_RETURN_IF_ERROR(
      ReadChoice<ExternalPoseMode>(r, n, "external_pose_mode", "inputs.external_pose_mode",
                                   {{"ignore", ExternalPoseMode::kIgnore},
                                    {"pass_through", ExternalPoseMode::kPassThrough},
                                    {"fuse", ExternalPoseMode::kFuse}},
                                   c.node.pipeline.localizer.external_pose_mode));
  FLEETMAP_RETURN_IF_ERROR(ReadSick(r, Section(n, "sick"), c.sick));
  return ReadCan(r, Section(n, "can"), c.can);
}

core::Status ReadLocalization(const YamlReader& r, const YAML::Node& n, LocalizerOptions& l) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "localization",
                {"max_beams", "min_particles", "max_particles", "update_min_translation_m",
                 "update_min_rotation_rad", "w_avg_model", "external_sigma_xy_m",
                 "external_sigma_theta_rad", "lost_after_s", "lost_explained_share",
                 "lost_max_search_period_s", "relocalize_margin", "seed"}));
  READ_AS(int, n, "max_beams", "localization.", l.max_beams);
  READ_AS(int, n, "min_particles", "localization.", l.kld.min_particles);
  READ_AS(int, n, "max_particles", "localization.", l.kld.max_particles);
  READ_NUMBER(n, "update_min_translation_m", "localization.", l.update_min_translation_m);
  READ_NUMBER(n, "update_min_rotation_rad", "localization.", l.update_min_rotation_rad);
  FLEETMAP_RETURN_IF_ERROR(ReadChoice<WAvgModel>(
      r, n, "w_avg_model", "localization.w_avg_model",
      {{"beam", WAvgModel::kBeamModel}, {"likelihood_field", WAvgModel::kLikelihoodField}},
      l.w_avg_model));
  READ_NUMBER(n, "external_sigma_xy_m", "localization.", l.external_sigma_xy_m);
  READ_NUMBER(n, "external_sigma_theta_rad", "localization.", l.external_sigma_theta_rad);
  READ_NUMBER(n, "lost_after_s", "localization.", l.lost_after_s);
  READ_NUMBER(n, "lost_explained_share", "localization.", l.lost_explained_share);
  READ_NUMBER(n, "lost_max_search_period_s", "localization.", l.lost_max_search_period_s);
  READ_NUMBER(n, "relocalize_margin", "localization.", l.relocalize_margin);
  READ_AS(uint32_t, n, "seed", "localization.", l.seed);
  return core::OkStatus();
}

core::Status ReadDivergence(const YamlReader& r, const YAML::Node& n, DivergenceOptions& d) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "divergence",
                {"rule", "alpha_slow", "alpha_fast", "start_above", "stop_below", "min_duration_s",
                 "max_duration_s", "rotation_freeze_radps", "map_at_start"}));
  FLEETMAP_RETURN_IF_ERROR(ReadChoice<DivergenceRule>(
      r, n, "rule", "divergence.rule",
      {{"hysteresis", DivergenceRule::kHysteresis}, {"paper", DivergenceRule::kPaper}}, d.rule));
  READ_NUMBER(n, "alpha_slow", "divergence.", d.alpha_slow);
  READ_NUMBER(n, "alpha_fast", "divergence.", d.alpha_fast);
  READ_NUMBER(n, "start_above", "divergence.", d.start_above);
  READ_NUMBER(n, "stop_below", "divergence.", d.stop_below);
  READ_NUMBER(n, "min_duration_s", "divergence.", d.min_duration_s);
  READ_NUMBER(n, "max_duration_s", "divergence.", d.max_duration_s);
  READ_NUMBER(n, "rotation_freeze_radps", "divergence.", d.rotation_freeze_radps);
  READ_AS(bool, n, "map_at_start", "divergence.", d.map_at_start);
  return core::OkStatus();
}

core::Status ReadBuilder(const YamlReader& r, const YAML::Node& n, TempMapBuilderOptions& b) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, n, "builder",
                                     {"size_m", "max_duration_s", "edge_margin_m", "levels",
                                      "odometry_sigma_m", "odometry_sigma_per_m"}));
  READ_NUMBER(n, "size_m", "builder.", b.mapper.map.size_m);
  READ_NUMBER(n, "max_duration_s", "builder.", b.max_duration_s);
  READ_NUMBER(n, "edge_margin_m", "builder.", b.edge_margin_m);
  READ_AS(int, n, "levels", "builder.", b.mapper.map.levels);
  READ_NUMBER(n, "odometry_sigma_m", "builder.", b.mapper.matcher.prior_sigma_xy_m);
  READ_NUMBER(n, "odometry_sigma_per_m", "builder.", b.mapper.matcher.prior_sigma_xy_per_m);
  return core::OkStatus();
}

core::Status ReadCandidateWatch(const YamlReader& r, const YAML::Node& n, AgentPipelineOptions& p) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "candidate_watch",
                {"pass_margin_m", "hit_margin_m", "min_free_scans", "max_range_m", "max_sigma_m",
                 "hold_gap_s", "report_held_s"}));
  CandidateWatchOptions& w = p.candidate_watch;
  READ_NUMBER(n, "pass_margin_m", "candidate_watch.", w.pass_margin_m);
  READ_NUMBER(n, "hit_margin_m", "candidate_watch.", w.hit_margin_m);
  READ_AS(int, n, "min_free_scans", "candidate_watch.", w.min_free_scans);
  READ_NUMBER(n, "max_range_m", "candidate_watch.", w.max_range_m);
  READ_NUMBER(n, "max_sigma_m", "candidate_watch.", p.candidate_watch_max_sigma_m);
  READ_NUMBER(n, "hold_gap_s", "candidate_watch.", w.hold_gap_s);
  READ_NUMBER(n, "report_held_s", "candidate_watch.", w.report_held_s);
  return core::OkStatus();
}

core::Status ReadOutbox(const YamlReader& r, const YAML::Node& n, OutboxOptions& o) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, n, "outbox",
                                     {"first_resend_s", "max_resend_s", "max_pending_maps",
                                      "tile_size_cells", "retain_merged_s", "max_retained_bytes"}));
  READ_NUMBER(n, "first_resend_s", "outbox.", o.first_resend_s);
  READ_NUMBER(n, "max_resend_s", "outbox.", o.max_resend_s);
  READ_AS(int, n, "max_pending_maps", "outbox.", o.max_pending_maps);
  READ_AS(int, n, "tile_size_cells", "outbox.", o.tile_size_cells);
  READ_NUMBER(n, "retain_merged_s", "outbox.", o.retain_merged_s);
  READ_AS(int64_t, n, "max_retained_bytes", "outbox.", o.max_retained_bytes);
  return core::OkStatus();
}

core::Status ReadLastPose(const YamlReader& r, const YAML::Node& n, KeptPoseOptions& o) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "last_pose", {"period_s", "same_odometry_m", "same_odometry_rad"}));
  READ_NUMBER(n, "period_s", "last_pose.", o.period_s);
  READ_NUMBER(n, "same_odometry_m", "last_pose.", o.same_odometry_m);
  READ_NUMBER(n, "same_odometry_rad", "last_pose.", o.same_odometry_rad);
  return core::OkStatus();
}

core::Status ReadRates(const YamlReader& r, const YAML::Node& n, AgentConfig& c) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "rates",
                {"status_period_s", "map_request_period_s", "max_queued_scans", "loop_wait_s",
                 "shutdown_drain_s", "uplink_tiles_per_s", "uplink_burst_tiles"}));
  READ_NUMBER(n, "status_period_s", "rates.", c.node.status_period_s);
  READ_NUMBER(n, "map_request_period_s", "rates.", c.node.map.request_period_s);
  READ_AS(int, n, "max_queued_scans", "rates.", c.node.queue.max_queued_scans);
  READ_NUMBER(n, "loop_wait_s", "rates.", c.loop_wait_s);
  READ_NUMBER(n, "shutdown_drain_s", "rates.", c.shutdown_drain_s);
  READ_NUMBER(n, "uplink_tiles_per_s", "rates.", c.node.uplink_pacer.rate_per_s);
  READ_NUMBER(n, "uplink_burst_tiles", "rates.", c.node.uplink_pacer.burst);
  return core::OkStatus();
}

core::Status ReadLinks(const YamlReader& r, const YAML::Node& root, AgentConfig& c) {
  if (const YAML::Node u = Section(root, "urls")) {
    FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, u, "urls", {"sensor", "uplink", "downlink"}));
    READ_AS(std::string, u, "sensor", "urls.", c.urls.sensor);
    READ_AS(std::string, u, "uplink", "urls.", c.urls.uplink);
    READ_AS(std::string, u, "downlink", "urls.", c.urls.downlink);
  }
  if (const YAML::Node m = Section(root, "map_updates")) {
    FLEETMAP_RETURN_IF_ERROR(
        CheckKeys(r, m, "map_updates", {"tile_size_cells", "max_buffered_versions"}));
    READ_AS(int, m, "tile_size_cells", "map_updates.", c.node.map.tile_size_cells);
    READ_AS(int, m, "max_buffered_versions", "map_updates.", c.node.map.max_buffered_versions);
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

#undef READ_NUMBER
#undef READ_AS

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
