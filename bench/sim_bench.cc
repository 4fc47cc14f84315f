// The simulator's speed: one vehicle with an S300 (541 beams, 25 Hz) on the LivingLab
// addition scenario, as simulated seconds per wall-clock second.
#include <benchmark/benchmark.h>

#include "bench/figure_reporter.h"
#include "sim/simulator.h"

namespace fleetmap::bench {
namespace {

constexpr double kSimulatedSeconds = 20.0;

const sim::World& AdditionWorld() {
  static const sim::World world = [] {
    auto w =
        sim::World::Load(std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/addition.yaml");
    if (!w.ok()) {
      std::fprintf(stderr, "sim_bench: %s\n", w.status().ToString().c_str());
      std::exit(1);
    }
    return std::move(w).value();
  }();
  return world;
}

void BM_SimulateOneVehicle(benchmark::State& state) {
  for (auto _ : state) {
    sim::Simulator simulator(&AdditionWorld());
    while (auto e = simulator.Next()) {
      if (sim::EventTime(*e) > kSimulatedSeconds) break;
      benchmark::DoNotOptimize(e);
    }
  }
}
BENCHMARK(BM_SimulateOneVehicle)->Unit(benchmark::kMillisecond);

void BM_OneScan(benchmark::State& state) {
  sim::Simulator simulator(&AdditionWorld());
  for (auto _ : state) {
    auto e = simulator.Next();
    if (!e) simulator = sim::Simulator(&AdditionWorld());
  }
}
BENCHMARK(BM_OneScan)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fleetmap::bench

int main(int argc, char** argv) {
  using namespace fleetmap::bench;
  RateFigure("BM_SimulateOneVehicle", "sim.realtime_factor", "x", kSimulatedSeconds);
  return RunBenchmarksAndPrintFigures(argc, argv);
}
