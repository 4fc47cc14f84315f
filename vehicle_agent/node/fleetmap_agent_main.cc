// fleetmap-agent: one vehicle's agent over LCM (docs/agent_process.md). The work is in
// AgentNode; this file reads the command line, opens the links and inputs, runs the loop
// and reports. See --help.
#include <signal.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/map/map_io.h"
#include "vehicle_agent/node/agent_flags.h"
#include "vehicle_agent/node/agent_loop.h"

namespace {

using namespace fleetmap;
using namespace fleetmap::vehicle_agent::node;

volatile std::sig_atomic_t g_stop = 0;
void OnSignal(int) { g_stop = 1; }

void InstallSignals() {
  struct sigaction action {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a wait in poll() returns at once
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

double SteadyNowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double WallNowS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

LogSink MakeLog(const std::string& id, bool quiet) {
  return [id, quiet](LogLevel level, const std::string& line) {
    if (quiet && level == LogLevel::kInfo) return;
    std::fprintf(stderr, "agent %s: %s%s\n", id.c_str(),
                 level == LogLevel::kWarning ? "warning: " : "", line.c_str());
  };
}

int Fail(const std::string& what, int code) {
  std::fprintf(stderr, "fleetmap-agent: %s\n", what.c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  core::Result<AgentCommandLine> command = ParseAgentCommandLine(args);
  if (!command.ok()) return Fail(command.status().ToString() + " (see --help)", 2);
  if (command->help) {
    std::fputs(AgentUsage().c_str(), stdout);
    return 0;
  }
  if (command->version) {
    std::printf("fleetmap-agent %s\n", command->config.node.software_version.c_str());
    return 0;
  }
  AgentConfig& config = command->config;
  const std::string id = config.node.pipeline.vehicle_id;
  const LogSink log = MakeLog(id, config.quiet);

  std::optional<core::OccupancyGrid> static_map;
  if (!config.map_yaml.empty()) {
    core::Result<core::LoadedMap> loaded = core::LoadMapServerMap(config.map_yaml);
    if (!loaded.ok()) return Fail("--map: " + loaded.status().ToString(), 1);
    static_map = std::move(loaded->grid);
  }
  if (!config.key_file.empty()) {
    core::Result<auth::Key> key = auth::ReadKeyFile(config.key_file);
    if (!key.ok()) return Fail("--key-file: " + key.status().ToString(), 1);
    config.node.fleet_key = *key;
  } else {
    log(LogLevel::kInfo, "no fleet key: messages are not authenticated");
  }
  // The node runs on the monotonic clock; what it sends is stamped in wall-clock time.
  config.node.utime_offset_s = WallNowS() - SteadyNowS();

  core::Result<std::unique_ptr<AgentLinks>> links = AgentLinks::Open(config.urls);
  if (!links.ok()) return Fail(links.status().ToString(), 1);
  core::Result<std::unique_ptr<AgentNode>> node =
      AgentNode::Create(config.node, links->get(), log, std::move(static_map), SteadyNowS());
  if (!node.ok()) return Fail(node.status().ToString(), 1);
  (*links)->Subscribe(node->get(), SteadyNowS);

  LoopSources sources;
  sources.links = links->get();
  std::unique_ptr<SickScanInput> scanner;
  if (config.scan_source == ScanSource::kSick) {
    scanner = std::make_unique<SickScanInput>(config.sick, log);
    sources.scanner = scanner.get();
  }
  std::unique_ptr<CanOdometryInput> odometry;
  if (config.odom_source == OdomSource::kCan) {
    core::Result<std::unique_ptr<CanOdometryInput>> opened = CanOdometryInput::Open(config.can);
    if (!opened.ok()) return Fail(opened.status().ToString(), 1);
    odometry = std::move(opened).value();
    sources.odometry = odometry.get();
  }
  InstallSignals();
  log(LogLevel::kInfo,
      std::string("running: ") +
          (config.map_yaml.empty() ? "waiting for the aggregator's map"
                                   : "static map " + config.map_yaml + " as version 0") +
          (scanner ? ", scans from " + scanner->endpoint() : ", scans from SCAN_" + id) +
          ", uplink " + config.urls.uplink + ", downlink " + config.urls.downlink);

  LoopOptions loop;
  loop.wait_s = config.loop_wait_s;
  loop.duration_s = config.duration_s;
  loop.shutdown_drain_s = config.shutdown_drain_s;
  const core::Status ran = RunAgentLoop(**node, sources, loop, &g_stop, SteadyNowS);
  int code = 0;
  if (!ran.ok()) code = Fail(ran.ToString(), 1);

  const AgentNode& n = **node;
  if (!config.final_map_yaml.empty()) {
    if (!n.map().has_map()) {
      code = Fail("--final-map: no map to write (no keyframe arrived)", 1);
    } else {
      const core::Status saved = core::SaveMapServerMap(n.map().map(), config.final_map_yaml);
      if (!saved.ok()) code = Fail("--final-map: " + saved.ToString(), 1);
    }
  }
  std::printf("agent %s: scans %lld map_version %d tempmaps %lld\n", id.c_str(),
              static_cast<long long>(n.counters().scans), n.map_version(),
              static_cast<long long>(n.counters().tempmaps_closed));
  std::fflush(stdout);
  return code;
}
