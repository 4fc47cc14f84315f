// fleetmap-lan-tool: reads what a LAN experiment (tools/lan/fleetmap-lan-experiment)
// recorded, and prepares its maps. See --help.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/map_io.h"
#include "core/version.h"
#include "tools/lan/change_cost.h"
#include "tools/lan/codec_sweep.h"
#include "tools/lan/lan_log.h"
#include "tools/lan/map_resample.h"
#include "tools/lan/status_summary.h"

namespace {

using namespace fleetmap;

constexpr const char* kUsage = R"(usage: fleetmap-lan-tool COMMAND ARGS

commands:
  status [--until-utime U] LOG...
                    the last STATUS_<process> heartbeat of every process in the LCM logs
                    (lcm-logger files of the uplink and downlink): `status.<process>.<counter>`
                    lines and `status.agents.<counter>` sums over the agents; with
                    --until-utime only heartbeats sent before U (microseconds since 1970)
  codec LOG...      every map tile in the logs (TEMPMAP_<id>, MAP_DELTA, MAP_KEYFRAME)
                    encoded again with raw8 (1 byte per cell), none, zlib 1/6/9 and
                    zstd 1/3/9/19: `codec.<group>.<variant>.bytes` lines (LCM payload bytes)
  changes LOG...    the cost of one map change on the downlink: tile delta, whole keyframe
                    and a ROS nav_msgs/OccupancyGrid of the whole map: `changes.*` lines
  resample MAP.yaml OUT.yaml --resolution M
                    the map at a coarser resolution (a whole multiple of the map's): a cell
                    is occupied when any cell it covers is, free when half of them are
Figures are printed as `name value unit` lines on stdout.
Exit status: 0 on success, 1 on a log or map that cannot be read or written, 2 on usage errors.
)";

int Fail(const core::Status& s) {
  std::fprintf(stderr, "fleetmap-lan-tool: %s\n", s.ToString().c_str());
  return 1;
}

int LogCommand(const std::string& command, std::vector<std::string> logs) {
  int64_t until_utime = 0;
  if (command == "status" && logs.size() >= 2 && logs[0] == "--until-utime") {
    char* end = nullptr;
    until_utime = std::strtoll(logs[1].c_str(), &end, 10);
    if (!end || *end != '\0' || until_utime <= 0) {
      std::fprintf(stderr, "fleetmap-lan-tool: --until-utime takes microseconds since 1970\n");
      return 2;
    }
    logs.erase(logs.begin(), logs.begin() + 2);
  }
  if (logs.empty()) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  auto messages = lan::ReadLogs(logs);
  if (!messages.ok()) return Fail(messages.status());
  std::string lines;
  if (command == "status")
    lines = lan::StatusFigureLines(lan::SummarizeStatus(*messages, until_utime));
  if (command == "codec")
    lines = lan::CodecFigureLines(lan::RecodeMapMessages(*messages, lan::DefaultCodecVariants()));
  if (command == "changes") lines = lan::ChangeCostFigureLines(lan::MeasureChangeCost(*messages));
  std::fputs(lines.c_str(), stdout);
  return 0;
}

int Resample(const std::vector<std::string>& args) {
  if (args.size() != 4 || args[2] != "--resolution") {
    std::fputs(kUsage, stderr);
    return 2;
  }
  char* end = nullptr;
  const double resolution_m = std::strtod(args[3].c_str(), &end);
  if (!end || *end != '\0' || !(resolution_m > 0)) {
    std::fprintf(stderr, "fleetmap-lan-tool: --resolution takes metres > 0\n");
    return 2;
  }
  auto map = core::LoadMapServerMap(args[0]);
  if (!map.ok()) return Fail(map.status());
  const double ratio = resolution_m / map->grid.geometry().resolution_m();
  const int factor = static_cast<int>(std::lround(ratio));
  if (factor < 1 || std::abs(ratio - factor) > 1e-6) {
    std::fprintf(stderr, "fleetmap-lan-tool: %g m is not a whole multiple of the map's %g m\n",
                 resolution_m, map->grid.geometry().resolution_m());
    return 2;
  }
  const core::OccupancyGrid coarse = lan::ResampleMap(map->grid, factor);
  const core::Status saved = core::SaveMapServerMap(coarse, args[1]);
  if (!saved.ok()) return Fail(saved);
  std::printf("wrote %s: %d x %d cells at %g m\n", args[1].c_str(), coarse.geometry().width(),
              coarse.geometry().height(), coarse.geometry().resolution_m());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (fleetmap::core::PrintVersionIfAsked(argc, argv, "fleetmap-lan-tool")) return 0;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string& command = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (command == "status" || command == "codec" || command == "changes")
    return LogCommand(command, rest);
  if (command == "resample") return Resample(rest);
  std::fprintf(stderr, "fleetmap-lan-tool: unknown command '%s'\n\n%s", command.c_str(), kUsage);
  return 2;
}
