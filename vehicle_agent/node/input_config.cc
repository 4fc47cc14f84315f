#include "vehicle_agent/node/input_config.h"

#include "vehicle_agent/node/config_reading.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using core::YamlReader;

core::Status ReadSick(const YamlReader& r, const YAML::Node& n, SickInputOptions& s) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(
      r, n, "inputs.sick",
      {"host", "port", "protocol", "connect_timeout_s", "first_scan_timeout_s", "silence_timeout_s",
       "reconnect_backoff_initial_s", "reconnect_backoff_max_s", "login", "start_measurement",
       "streaming", "range_min_m", "range_max_m", "range_channel", "intensity_channel"}));
  drivers::sick::ScannerClientOptions& o = s.client;
  FLEETMAP_READ_AS(r, std::string, n, "host", "inputs.sick.", o.host);
  FLEETMAP_READ_AS(r, int, n, "port", "inputs.sick.", o.port);
  if (n["protocol"]) {
    auto word = r.Get<std::string>(n, "protocol", "inputs.sick.protocol");
    if (!word.ok()) return word.status();
    auto protocol = drivers::sick::ParseColaProtocol(*word);
    if (!protocol.ok())
      return r.Error(n["protocol"], "inputs.sick.protocol", protocol.status().message());
    o.protocol = *protocol;
  }
  FLEETMAP_READ_NUMBER(r, n, "connect_timeout_s", "inputs.sick.", o.connect_timeout_s);
  FLEETMAP_READ_NUMBER(r, n, "first_scan_timeout_s", "inputs.sick.", o.first_scan_timeout_s);
  FLEETMAP_READ_NUMBER(r, n, "silence_timeout_s", "inputs.sick.", o.silence_timeout_s);
  FLEETMAP_READ_NUMBER(r, n, "reconnect_backoff_initial_s", "inputs.sick.",
                       o.reconnect_backoff_initial_s);
  FLEETMAP_READ_NUMBER(r, n, "reconnect_backoff_max_s", "inputs.sick.", o.reconnect_backoff_max_s);
  FLEETMAP_READ_AS(r, bool, n, "login", "inputs.sick.", o.login);
  FLEETMAP_READ_AS(r, bool, n, "start_measurement", "inputs.sick.", o.start_measurement);
  FLEETMAP_READ_AS(r, bool, n, "streaming", "inputs.sick.", o.streaming);
  FLEETMAP_READ_NUMBER(r, n, "range_min_m", "inputs.sick.", s.conversion.range_min_m);
  FLEETMAP_READ_NUMBER(r, n, "range_max_m", "inputs.sick.", s.conversion.range_max_m);
  FLEETMAP_READ_AS(r, std::string, n, "range_channel", "inputs.sick.", s.conversion.range_channel);
  FLEETMAP_READ_AS(r, std::string, n, "intensity_channel", "inputs.sick.",
                   s.conversion.intensity_channel);
  return core::OkStatus();
}

core::Status ReadCan(const YamlReader& r, const YAML::Node& n, CanInputOptions& c) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, n, "inputs.can", {"interface", "mapping", "mapping_file"}));
  FLEETMAP_READ_AS(r, std::string, n, "interface", "inputs.can.", c.socket.interface);
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

}  // namespace

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
  FLEETMAP_READ_AS(r, bool, n, "external_pose", "inputs.", c.node.use_external_pose);
  FLEETMAP_RETURN_IF_ERROR(
      ReadChoice<ExternalPoseMode>(r, n, "external_pose_mode", "inputs.external_pose_mode",
                                   {{"ignore", ExternalPoseMode::kIgnore},
                                    {"pass_through", ExternalPoseMode::kPassThrough},
                                    {"fuse", ExternalPoseMode::kFuse}},
                                   c.node.pipeline.localizer.external_pose_mode));
  FLEETMAP_RETURN_IF_ERROR(ReadSick(r, Section(n, "sick"), c.sick));
  return ReadCan(r, Section(n, "can"), c.can);
}

}  // namespace fleetmap::vehicle_agent::node
