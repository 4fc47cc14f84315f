#include "vehicle_agent/node/agent_flags.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>

namespace fleetmap::vehicle_agent::node {
namespace {

core::Result<double> ParseNumber(const std::string& text, const std::string& flag) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    return core::InvalidArgument(flag + ": '" + text + "' is not a number");
  return v;
}

core::Result<int> ParsePort(const std::string& text, const std::string& flag) {
  auto v = ParseNumber(text, flag);
  if (!v.ok()) return v.status();
  if (*v != std::floor(*v) || *v < 1 || *v > 65535)
    return core::InvalidArgument(flag + ": port must be 1..65535");
  return static_cast<int>(*v);
}

using Setter = std::function<core::Status(const std::string& value, AgentConfig& c)>;

// Every flag that takes a value, with what it sets.
const std::map<std::string, Setter>& ValueFlags() {
  static const std::map<std::string, Setter> flags = {
      {"--vehicle-id",
       [](const std::string& v, AgentConfig& c) {
         c.node.pipeline.vehicle_id = v;
         return CheckVehicleId(v);
       }},
      {"--map",
       [](const std::string& v, AgentConfig& c) {
         c.map_yaml = v;
         return core::OkStatus();
       }},
      {"--initial-pose",
       [](const std::string& v, AgentConfig& c) {
         auto pose = ParsePoseFlag(v, "--initial-pose");
         if (!pose.ok()) return pose.status();
         c.node.pipeline.localizer.initial_pose_in_map = *pose;
         c.node.initial_pose = InitialPoseSource::kGiven;
         c.initial_pose_explicit = true;
         return core::OkStatus();
       }},
      {"--scanner-mount",
       [](const std::string& v, AgentConfig& c) {
         auto pose = ParsePoseFlag(v, "--scanner-mount");
         if (!pose.ok()) return pose.status();
         c.node.pipeline.scanner_in_base = *pose;
         return core::OkStatus();
       }},
      {"--state-dir",
       [](const std::string& v, AgentConfig& c) {
         c.node.outbox.state_dir = v;
         return core::OkStatus();
       }},
      {"--key-file",
       [](const std::string& v, AgentConfig& c) {
         c.key_file = v;
         return core::OkStatus();
       }},
      {"--sensor-url",
       [](const std::string& v, AgentConfig& c) {
         c.urls.sensor = v;
         return core::OkStatus();
       }},
      {"--uplink-url",
       [](const std::string& v, AgentConfig& c) {
         c.urls.uplink = v;
         return core::OkStatus();
       }},
      {"--downlink-url",
       [](const std::string& v, AgentConfig& c) {
         c.urls.downlink = v;
         return core::OkStatus();
       }},
      {"--final-map",
       [](const std::string& v, AgentConfig& c) {
         c.final_map_yaml = v;
         return core::OkStatus();
       }},
      {"--duration",
       [](const std::string& v, AgentConfig& c) {
         auto d = ParseNumber(v, "--duration");
         if (!d.ok()) return d.status();
         if (*d < 0) return core::InvalidArgument("--duration must be >= 0");
         c.duration_s = *d;
         return core::OkStatus();
       }},
      {"--sick",
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
  };
  return flags;
}

// Splits "--flag=value"; the value comes from the next argument otherwise.
bool SplitInline(const std::string& arg, std::string& flag, std::string& value) {
  const size_t eq = arg.find('=');
  if (arg.rfind("--", 0) != 0 || eq == std::string::npos) return false;
  flag = arg.substr(0, eq);
  value = arg.substr(eq + 1);
  return true;
}

}  // namespace

core::Result<core::Pose2> ParsePoseFlag(const std::string& text, const std::string& flag) {
  double v[3];
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos))
      return core::InvalidArgument(flag + " takes X,Y,THETA (metres, metres, radians)");
    auto n = ParseNumber(text.substr(start, i < 2 ? comma - start : std::string::npos), flag);
    if (!n.ok()) return n.status();
    v[i] = *n;
    start = comma + 1;
  }
  return core::Pose2(v[0], v[1], v[2]);
}

core::Result<AgentCommandLine> ParseAgentCommandLine(const std::vector<std::string>& args) {
  AgentCommandLine out;
  // Pairs of (flag, value) in order; the configuration file is read first.
  std::vector<std::pair<std::string, std::string>> values;
  std::string config_path;
  bool quiet = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    std::string flag = arg, value;
    if (arg == "--help" || arg == "-h") {
      out.help = true;
      return out;
    }
    if (arg == "--version") {
      out.version = true;
      return out;
    }
    if (arg == "--quiet") {
      quiet = true;
      continue;
    }
    const bool inline_value = SplitInline(arg, flag, value);
    if (flag != "--config" && !ValueFlags().count(flag))
      return core::InvalidArgument("unknown argument '" + arg + "'");
    if (!inline_value) {
      if (i + 1 >= args.size()) return core::InvalidArgument(flag + " needs a value");
      value = args[++i];
    }
    if (flag == "--config") {
      config_path = value;
    } else {
      values.emplace_back(flag, value);
    }
  }
  if (!config_path.empty()) {
    auto loaded = LoadAgentConfig(config_path);
    if (!loaded.ok()) return loaded.status();
    out.config = std::move(loaded).value();
  }
  for (const auto& [flag, value] : values)
    FLEETMAP_RETURN_IF_ERROR(ValueFlags().at(flag)(value, out.config));
  out.config.quiet = quiet;
  out.config.FinishDefaults();
  FLEETMAP_RETURN_IF_ERROR(out.config.Validate());
  return out;
}

std::string AgentUsage() {
  return R"(usage: fleetmap-agent [--config FILE.yaml] [flags]

The on-board agent of one vehicle (docs/agent_process.md): localizes on the current map,
detects where the map no longer explains the laser, sends temporary maps to the aggregator
and follows the map versions the aggregator sends back.
  in:  SCAN_<ID>, ODOM_<ID>, EXTPOSE_<ID> (sensor link, or a SICK scanner / CAN odometry);
       TEMPMAP_ACK, MAP_DELTA, MAP_KEYFRAME, STATUS_aggregator (downlink)
  out: POSE_<ID>, DIVERGENCE_<ID>, TEMPMAP_<ID>, MAP_REQUEST, STATUS_agent_<ID> (uplink)
flags (override the configuration file):
  --config FILE         YAML configuration; every key in docs/agent_process.md
  --vehicle-id ID       the vehicle (A-Z a-z 0-9 _ -; required here or in the file)
  --map FILE            static map (map_server YAML), held as version 0; without: wait for
                        the aggregator's keyframe before localizing
  --initial-pose X,Y,THETA   first pose on the map (m, m, rad); without: global localization,
                        or the first external pose when inputs.external_pose is on
  --scanner-mount X,Y,THETA  scanner pose in the vehicle frame (m, m, rad)    [0,0,0]
  --state-dir DIR       unacknowledged temporary maps kept here survive restarts
  --key-file FILE       the fleet key (docs/security.md, chmod 600): sign what is sent,
                        accept only downlink messages the aggregator signed
  --sensor-url URL      [udpm://239.255.76.69:7669?ttl=0]
  --uplink-url URL      [udpm://239.255.76.67:7667?ttl=0]
  --downlink-url URL    [udpm://239.255.76.68:7668?ttl=0]
  --sick HOST:PORT      scans from a SICK scanner over TCP instead of SCAN_<ID>
  --final-map OUT.yaml  write the current map there at exit (map_server YAML + PGM)
  --duration S          stop after S seconds (0: until SIGINT/SIGTERM)               [0]
  --quiet               only warnings, errors and the final line
  --version, -h/--help
SIGINT/SIGTERM: a temporary map being built is closed into the outbox (and the state
folder) and sent, its acknowledgement awaited up to rates.shutdown_drain_s (2 s), then the
final map is written and the last line is
  agent <ID>: scans N map_version V tempmaps T
Exit status: 0 stopped cleanly, 1 runtime failure (LCM, files), 2 bad command line or config.
LCM multicast needs a route: run scripts/setup_multicast.sh (root) on a single host.
)";
}

}  // namespace fleetmap::vehicle_agent::node
