// fleetmap-sim-candump: writes the odometry of a simulated vehicle as the CANopen frames of
// its two drive nodes, in candump log format, for canplayer to replay onto a (v)can bus.
#include <cstdio>
#include <string>

#include "core/command_line.h"
#include "sim/can/sim_can_log.h"

int main(int argc, char** argv) {
  using namespace fleetmap;
  CLI::App app(
      "Writes the odometry of a simulated vehicle as the CANopen frames of its two drive\n"
      "nodes, in candump log format. Replay: canplayer -I LOG vcan0=can0\n"
      "Exit status: 0 written, 1 the scenario, the CAN mapping or the log failed, 2 usage "
      "errors.",
      "fleetmap-sim-candump");
  core::AddVersionFlag(app);
  std::string scenario, out, can_yaml;
  sim::can::SimCanLogOptions options;
  app.add_option("--scenario", scenario, "the scenario (docs/scenario.md)")->required();
  app.add_option("--out", out, "the candump log to write")->required();
  app.add_option("--vehicle", options.vehicle, "index of the scenario's vehicle")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  app.add_option("--duration", options.duration_s, "simulated seconds (0: the whole scenario)")
      ->check(core::Finite())
      ->capture_default_str();
  app.add_option("--can", can_yaml,
                 "drive-node mapping (docs/drivers.md); default: SYNC 0x80, nodes 1 and 2, "
                 "TPDO1");
  app.add_option("--interface", options.interface, "the interface written into every record")
      ->capture_default_str();
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  if (!can_yaml.empty()) {
    auto can = drivers::can::LoadDiffDriveCanOptions(can_yaml);
    if (!can.ok()) return std::fprintf(stderr, "%s\n", can.status().ToString().c_str()), 1;
    options.can = *can;
  }
  auto world = sim::World::Load(scenario);
  if (!world.ok()) return std::fprintf(stderr, "%s\n", world.status().ToString().c_str()), 1;
  auto log = sim::can::RecordOdometryAsCan(*world, options);
  if (!log.ok()) return std::fprintf(stderr, "%s\n", log.status().ToString().c_str()), 1;
  if (auto s = drivers::can::WriteCandumpLog(out, log->records); !s.ok()) {
    return std::fprintf(stderr, "%s\n", s.ToString().c_str()), 1;
  }
  std::printf("wrote %zu frames (%zu odometry samples) to %s\n", log->records.size(),
              log->odometry.size(), out.c_str());
  return 0;
}
