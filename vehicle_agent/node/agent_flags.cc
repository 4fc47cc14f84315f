#include "vehicle_agent/node/agent_flags.h"

#include <cmath>
#include <functional>
#include <map>

#include "core/command_line.h"

namespace fleetmap::vehicle_agent::node {
namespace {

constexpr char kDescription[] =
    R"(The on-board agent of one vehicle (docs/agent_process.md): localizes on the current map,
detects where the map no longer explains the laser, sends temporary maps to the aggregator
and follows the map versions the aggregator sends back.
  in:  SCAN_<ID>, ODOM_<ID>, EXTPOSE_<ID> (sensor link, or a SICK scanner / CAN odometry);
       TEMPMAP_ACK, MAP_DELTA, MAP_KEYFRAME, STATUS_aggregator (downlink)
  out: POSE_<ID>, DIVERGENCE_<ID>, TEMPMAP_<ID>, MAP_REQUEST, STATUS_agent_<ID> (uplink)
--config FILE.yaml is read first; the other flags override single keys of it.)";

constexpr char kFooter[] =
    R"(SIGINT/SIGTERM: a temporary map being built is closed into the outbox (and the state
folder) and sent, its acknowledgement awaited up to rates.shutdown_drain_s (2 s), then the
final map is written and the last line is
  agent <ID>: scans N map_version V tempmaps T
Exit status: 0 stopped cleanly, 1 runtime failure (LCM, files), 2 bad command line or config.
LCM multicast needs a route: run scripts/setup_multicast.sh (root) on a single host.)";

core::Result<int> ParsePort(const std::string& text, const std::string& flag) {
  auto v = core::ParseNumber(text, flag);
  if (!v.ok()) return v.status();
  if (*v != std::floor(*v) || *v < 1 || *v > 65535)
    return core::InvalidArgument(flag + ": port must be 1..65535");
  return static_cast<int>(*v);
}

using Setter = std::function<core::Status(const std::string& value, AgentConfig& c)>;

// A flag that overrides one key of the configuration.
struct ValueFlag {
  const char* name;
  const char* value_name;
  const char* help;
  Setter set;
};

core::Status SetString(std::string& field, const std::string& value) {
  field = value;
  return core::OkStatus();
}

const std::vector<ValueFlag>& ValueFlags() {
  static const std::vector<ValueFlag> flags = {
      {"--vehicle-id", "ID", "the vehicle (A-Z a-z 0-9 _ -; required here or in the file)",
       [](const std::string& v, AgentConfig& c) {
         c.node.pipeline.vehicle_id = v;
         return CheckVehicleId(v);
       }},
      {"--map", "FILE",
       "static map (map_server YAML), held as version 0; without: wait for the aggregator's "
       "keyframe before localizing",
       [](const std::string& v, AgentConfig& c) { return SetString(c.map_yaml, v); }},
      {"--initial-pose", "X,Y,THETA",
       "first pose on the map (m, m, rad); without: global localization, or the first "
       "external pose when inputs.external_pose is on",
       [](const std::string& v, AgentConfig& c) {
         auto pose = ParsePoseFlag(v, "--initial-pose");
         if (!pose.ok()) return pose.status();
         c.node.pipeline.localizer.initial_pose_in_map = *pose;
         c.node.initial_pose = InitialPoseSource::kGiven;
         c.initial_pose_explicit = true;
         return core::OkStatus();
       }},
      {"--scanner-mount", "X,Y,THETA", "scanner pose in the vehicle frame (m, m, rad) [0,0,0]",
       [](const std::string& v, AgentConfig& c) {
         auto pose = ParsePoseFlag(v, "--scanner-mount");
         if (!pose.ok()) return pose.status();
         c.node.pipeline.scanner_in_base = *pose;
         return core::OkStatus();
       }},
      {"--state-dir", "DIR", "unacknowledged temporary maps kept here survive restarts",
       [](const std::string& v, AgentConfig& c) { return SetString(c.node.outbox.state_dir, v); }},
      {"--key-file", "FILE",
       "the fleet key (docs/security.md, chmod 600): sign what is sent, accept only downlink "
       "messages the aggregator signed",
       [](const std::string& v, AgentConfig& c) { return SetString(c.key_file, v); }},
      {"--sensor-url", "URL", "[udpm://239.255.76.69:7669?ttl=0]",
       [](const std::string& v, AgentConfig& c) { return SetString(c.urls.sensor, v); }},
      {"--uplink-url", "URL", "[udpm://239.255.76.67:7667?ttl=0]",
       [](const std::string& v, AgentConfig& c) { return SetString(c.urls.uplink, v); }},
      {"--downlink-url", "URL", "[udpm://239.255.76.68:7668?ttl=0]",
       [](const std::string& v, AgentConfig& c) { return SetString(c.urls.downlink, v); }},
      {"--sick", "HOST:PORT", "scans from a SICK scanner over TCP instead of SCAN_<ID>",
       [](const std::string& v, AgentConfig& c) {
         const size_t colon = v.rfind(':');
         if (colon == std::string::npos || colon == 0)
           return core::InvalidArgument("--sick takes HOST:PORT");
         auto port = ParsePort(v.substr(colon + 1), "--sick");
         if (!port.ok()) return port.status();
         c.sick.client.host = v.substr(0, colon);
         c.sick.client.port = *port;
         c.scan_source = ScanSource::kSick;
         return core::OkStatus();
       }},
      {"--final-map", "OUT.yaml", "write the current map there at exit (map_server YAML + PGM)",
       [](const std::string& v, AgentConfig& c) { return SetString(c.final_map_yaml, v); }},
      {"--duration", "S", "stop after S seconds (0: until SIGINT/SIGTERM) [0]",
       [](const std::string& v, AgentConfig& c) {
         auto d = core::ParseNumber(v, "--duration");
         if (!d.ok()) return d.status();
         if (*d < 0) return core::InvalidArgument("--duration must be >= 0");
         c.duration_s = *d;
         return core::OkStatus();
       }},
  };
  return flags;
}

// What the command line said, before the configuration file is read.
struct GivenFlags {
  std::string config_path;
  bool quiet = false;
  std::map<std::string, std::string> values;  // by flag name, for the flags given
};

// The app reads into `given`; its help is the agent's usage.
void DefineFlags(CLI::App& app, GivenFlags& given) {
  app.description(kDescription);
  app.footer(kFooter);
  core::AddVersionFlag(app);
  app.add_option("--config", given.config_path,
                 "YAML configuration; every key in docs/agent_process.md")
      ->type_name("FILE");
  for (const ValueFlag& flag : ValueFlags())
    app.add_option(flag.name, given.values[flag.name], flag.help)->type_name(flag.value_name);
  app.add_flag("--quiet", given.quiet, "only warnings, errors and the final line");
}

}  // namespace

core::Result<core::Pose2> ParsePoseFlag(const std::string& text, const std::string& flag) {
  double v[3];
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos))
      return core::InvalidArgument(flag + " takes X,Y,THETA (metres, metres, radians)");
    auto n = core::ParseNumber(text.substr(start, i < 2 ? comma - start : std::string::npos), flag);
    if (!n.ok()) return n.status();
    v[i] = *n;
    start = comma + 1;
  }
  return core::Pose2(v[0], v[1], v[2]);
}

core::Result<AgentCommandLine> ParseAgentCommandLine(const std::vector<std::string>& args) {
  AgentCommandLine out;
  GivenFlags given;
  CLI::App app("", "fleetmap-agent");
  DefineFlags(app, given);
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 takes them reversed
  } catch (const CLI::CallForHelp&) {
    out.help = true;
    return out;
  } catch (const CLI::CallForVersion&) {
    out.version = true;
    return out;
  } catch (const CLI::ParseError& e) {
    return core::InvalidArgument(e.what());
  }
  if (!given.config_path.empty()) {
    auto loaded = LoadAgentConfig(given.config_path);
    if (!loaded.ok()) return loaded.status();
    out.config = std::move(loaded).value();
  }
  for (const ValueFlag& flag : ValueFlags())
    if (app.count(flag.name) > 0)
      FLEETMAP_RETURN_IF_ERROR(flag.set(given.values[flag.name], out.config));
  out.config.quiet = given.quiet;
  out.config.FinishDefaults();
  FLEETMAP_RETURN_IF_ERROR(out.config.Validate());
  return out;
}

std::string AgentUsage() {
  GivenFlags given;
  CLI::App app("", "fleetmap-agent");
  DefineFlags(app, given);
  return app.help();
}

}  // namespace fleetmap::vehicle_agent::node
