// fleetmap-sim-candump: writes the odometry of a simulated vehicle as the CANopen frames of
// its two drive nodes, in candump log format, for canplayer to replay onto a (v)can bus.
#include <cstdio>
#include <string>

#include "core/number_text.h"
#include "core/version.h"
#include "tools/simcan/sim_can_log.h"

namespace {

constexpr const char* kUsage = R"(usage: fleetmap-sim-candump --scenario S.yaml --out LOG
       [--vehicle N] [--duration S] [--can CAN.yaml] [--interface can0]
  --can   drive-node mapping (docs/drivers.md); defaults: SYNC 0x80, nodes 1 and 2, TPDO1
Replay: canplayer -I LOG vcan0=can0
)";

}  // namespace

int main(int argc, char** argv) {
  if (fleetmap::core::PrintVersionIfAsked(argc, argv, "fleetmap-sim-candump")) return 0;
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h"))
    return std::fputs(kUsage, stdout), 0;
  using namespace fleetmap;
  std::string scenario, out, can_yaml;
  simcan::SimCanLogOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    const std::string v = i + 1 < argc ? argv[i + 1] : "";
    if (k == "--scenario") {
      scenario = v;
    } else if (k == "--out") {
      out = v;
    } else if (k == "--vehicle") {
      auto n = core::ParseCount(v, k, 1000);
      if (!n.ok()) return std::fprintf(stderr, "%s\n", n.status().message().c_str()), 2;
      options.vehicle = *n;
    } else if (k == "--duration") {
      auto d = core::ParseNumber(v, k);
      if (!d.ok()) return std::fprintf(stderr, "%s\n", d.status().message().c_str()), 2;
      options.duration_s = *d;
    } else if (k == "--can") {
      can_yaml = v;
    } else if (k == "--interface") {
      options.interface = v;
    } else {
      return std::fputs(kUsage, stderr), 2;
    }
    ++i;
  }
  if (scenario.empty() || out.empty()) return std::fputs(kUsage, stderr), 2;
  if (!can_yaml.empty()) {
    auto can = drivers::can::LoadDiffDriveCanOptions(can_yaml);
    if (!can.ok()) return std::fprintf(stderr, "%s\n", can.status().ToString().c_str()), 1;
    options.can = *can;
  }
  auto world = sim::World::Load(scenario);
  if (!world.ok()) return std::fprintf(stderr, "%s\n", world.status().ToString().c_str()), 1;
  auto log = simcan::RecordOdometryAsCan(*world, options);
  if (!log.ok()) return std::fprintf(stderr, "%s\n", log.status().ToString().c_str()), 1;
  if (auto s = drivers::can::WriteCandumpLog(out, log->records); !s.ok()) {
    return std::fprintf(stderr, "%s\n", s.ToString().c_str()), 1;
  }
  std::printf("wrote %zu frames (%zu odometry samples) to %s\n", log->records.size(),
              log->odometry.size(), out.c_str());
  return 0;
}
