// The temporary-map builder per S300 scan (541 beams, 25 Hz) on the LivingLab addition
// scenario: scan matching on the multi-resolution map plus the map update when it is due
// (every 0.1 m or 0.1 rad), i.e. what a vehicle spends per scan while it builds a map.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <vector>

#include "bench/figure_reporter.h"
#include "sim/simulator.h"
#include "vehicle_agent/mapping/temp_map_builder.h"

namespace fleetmap::bench {
namespace {

struct Recorded {
  std::vector<core::LaserScan> scans;
  std::vector<core::Pose2> odometry_deltas;
  core::Pose2 mount;
};

// 20 s of one vehicle's scans with its noisy odometry between them.
const Recorded& Scans() {
  static const Recorded recorded = [] {
    auto world =
        sim::World::Load(std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/addition.yaml");
    if (!world.ok()) {
      std::fprintf(stderr, "tempmap_bench: %s\n", world.status().ToString().c_str());
      std::exit(1);
    }
    Recorded r;
    r.mount = world->scenario().vehicles[0].scanner_mount;
    sim::Simulator simulator(&*world);
    core::Pose2 odom, odom_at_last_scan;
    while (auto e = simulator.Next()) {
      if (sim::EventTime(*e) > 20.0) break;
      if (auto* o = std::get_if<sim::OdometryEvent>(&*e)) odom = o->odom_pose;
      if (auto* s = std::get_if<sim::ScanEvent>(&*e)) {
        r.scans.push_back(s->scan);
        r.odometry_deltas.push_back(core::Between(odom_at_last_scan, odom));
        odom_at_last_scan = odom;
      }
    }
    return r;
  }();
  return recorded;
}

void BM_TempMapUpdate(benchmark::State& state) {
  const Recorded& r = Scans();
  vehicle_agent::TempMapBuilder builder({});
  size_t i = 0;
  for (auto _ : state) {
    if (i == r.scans.size() || !builder.building()) {
      state.PauseTiming();
      builder.Close(0.0);
      builder.Start("bench", 1, r.scans[0].stamp_s, {});
      i = 0;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(builder.AddScan(r.scans[i], r.odometry_deltas[i], r.mount));
    ++i;
  }
}
BENCHMARK(BM_TempMapUpdate)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fleetmap::bench

int main(int argc, char** argv) {
  using namespace fleetmap::bench;
  TimeFigure("BM_TempMapUpdate", "agent.tempmap_update_us", "us");
  return RunBenchmarksAndPrintFigures(argc, argv);
}
