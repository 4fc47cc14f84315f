// fleetmap-lan-tool: reads what a LAN experiment (ops/lan/fleetmap-lan-experiment)
// recorded, and prepares its maps. See --help.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/command_line.h"
#include "core/map/map_io.h"
#include "ops/lan/ack_delays.h"
#include "ops/lan/change_cost.h"
#include "ops/lan/codec_sweep.h"
#include "ops/lan/lan_log.h"
#include "ops/lan/map_resample.h"
#include "ops/lan/status_summary.h"

namespace {

using namespace fleetmap;

int Fail(const core::Status& s) {
  std::fprintf(stderr, "fleetmap-lan-tool: %s\n", s.ToString().c_str());
  return 1;
}

// status, codec, changes, acks: figures of the recorded LCM logs.
int LogCommand(const std::string& command, const std::vector<std::string>& logs,
               int64_t until_utime) {
  auto messages = ops::lan::ReadLogs(logs);
  if (!messages.ok()) return Fail(messages.status());
  std::string lines;
  if (command == "status")
    lines = ops::lan::StatusFigureLines(ops::lan::SummarizeStatus(*messages, until_utime));
  if (command == "codec")
    lines = ops::lan::CodecFigureLines(
        ops::lan::RecodeMapMessages(*messages, ops::lan::DefaultCodecVariants()));
  if (command == "changes")
    lines = ops::lan::ChangeCostFigureLines(ops::lan::MeasureChangeCost(*messages));
  if (command == "acks")
    lines = ops::lan::AckDelayFigureLines(ops::lan::MeasureAckDelays(*messages));
  std::fputs(lines.c_str(), stdout);
  return 0;
}

int Resample(const std::string& in, const std::string& out, double resolution_m) {
  auto map = core::LoadMapServerMap(in);
  if (!map.ok()) return Fail(map.status());
  const double ratio = resolution_m / map->grid.geometry().resolution_m();
  const int factor = static_cast<int>(std::lround(ratio));
  if (factor < 1 || std::abs(ratio - factor) > 1e-6) {
    std::fprintf(stderr, "fleetmap-lan-tool: %g m is not a whole multiple of the map's %g m\n",
                 resolution_m, map->grid.geometry().resolution_m());
    return 2;
  }
  const core::OccupancyGrid coarse = ops::lan::ResampleMap(map->grid, factor);
  const core::Status saved = core::SaveMapServerMap(coarse, out);
  if (!saved.ok()) return Fail(saved);
  std::printf("wrote %s: %d x %d cells at %g m\n", out.c_str(), coarse.geometry().width(),
              coarse.geometry().height(), coarse.geometry().resolution_m());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "Reads what a LAN experiment (fleetmap-lan-experiment) recorded, and prepares its maps.\n"
      "Figures are printed as `name value unit` lines on stdout.\n"
      "Exit status: 0 on success, 1 on a log or map that cannot be read or written, 2 on "
      "usage errors.",
      "fleetmap-lan-tool");
  core::AddVersionFlag(app);
  app.require_subcommand(1);
  std::vector<std::string> logs;
  int64_t until_utime = 0;
  CLI::App* status = app.add_subcommand(
      "status",
      "the last STATUS_<process> heartbeat of every process in the LCM logs (lcm-logger files "
      "of the uplink and downlink): `status.<process>.<counter>` lines and "
      "`status.agents.<counter>` sums over the agents");
  status
      ->add_option("--until-utime", until_utime,
                   "only heartbeats sent before this time, microseconds since 1970")
      ->check(CLI::Range(int64_t{1}, std::numeric_limits<int64_t>::max()));
  CLI::App* codec = app.add_subcommand(
      "codec",
      "every map tile in the logs (TEMPMAP_<id>, MAP_DELTA, MAP_KEYFRAME) encoded again with "
      "raw8 (1 byte per cell), none, zlib 1/6/9 and zstd 1/3/9/19: "
      "`codec.<group>.<variant>.bytes` lines (LCM payload bytes)");
  CLI::App* changes = app.add_subcommand(
      "changes",
      "the cost of one map change on the downlink: tile delta, whole keyframe and a ROS "
      "nav_msgs/OccupancyGrid of the whole map: `changes.*` lines");
  CLI::App* acks = app.add_subcommand(
      "acks",
      "how long vehicles waited for the answer to a temporary map: from its last TEMPMAP_<id> "
      "tile to its final TEMPMAP_ACK, in uplink and downlink logs recorded on one host: "
      "`acks.*` lines");
  for (CLI::App* command : {status, codec, changes, acks})
    command->add_option("LOG", logs, "LCM logs")->required();
  CLI::App* resample = app.add_subcommand(
      "resample",
      "the map at a coarser resolution (a whole multiple of the map's): a cell is occupied "
      "when any cell it covers is, free when half of them are");
  std::string map_in, map_out;
  double resolution_m = 0.0;
  resample->add_option("MAP.yaml", map_in, "the map_server map to read")->required();
  resample->add_option("OUT.yaml", map_out, "the map_server map to write")->required();
  resample->add_option("--resolution", resolution_m, "metres per cell of the result")
      ->check(core::Positive())
      ->required();
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  if (resample->parsed()) return Resample(map_in, map_out, resolution_m);
  const CLI::App* command = app.get_subcommands().front();
  return LogCommand(command->get_name(), logs, until_utime);
}
