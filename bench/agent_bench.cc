// The whole on-board pipeline per S300 scan (541 beams, 25 Hz) on the LivingLab map:
// localization, W_avg, divergence and, while a change is seen, the temporary map; and the
// pipeline's peak resident memory over a 60 s run with a pallet placed on the route.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bench/figure_reporter.h"
#include "core/map/map_io.h"
#include "sim/simulator.h"
#include "vehicle_agent/agent_pipeline.h"

namespace fleetmap::bench {
namespace {

constexpr const char* kScenario = R"(
map: livinglab.yaml
duration_s: 60
seed: 3
objects:
  - {id: pallet, rect: {center: [16.0, 5.6], size: [1.2, 0.8]}, appear_s: 10}
vehicles:
  - {id: v1, route: [[6.0, 4.0], [50.0, 4.0]], speed_mps: 0.5, scanner_mount: [0.3, 0.0, 0.0]}
)";

struct Recording {
  core::OccupancyGrid map;
  core::Pose2 start, mount;
  std::vector<core::OdometrySample> odometry;  // the latest sample before each scan
  std::vector<core::LaserScan> scans;
};

Recording Record() {
  const std::string dir = std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/";
  const auto scenario = sim::ParseScenario(kScenario, dir + "agent_bench.yaml").value();
  Recording r;
  r.map = core::LoadMapServerMap(scenario.map_yaml).value().grid;
  const sim::World world = sim::World::Create(scenario, r.map).value();
  r.start = world.VehicleStateAt(0, 0).pose;
  r.mount = scenario.vehicles[0].scanner_mount;
  sim::Simulator simulator(&world);
  core::OdometrySample odom;
  while (auto e = simulator.Next()) {
    if (auto* o = std::get_if<sim::OdometryEvent>(&*e))
      odom = {o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps};
    if (auto* s = std::get_if<sim::ScanEvent>(&*e)) {
      r.odometry.push_back(odom);
      r.scans.push_back(s->scan);
    }
  }
  return r;
}

const Recording& Recorded() {
  static const Recording recording = Record();
  return recording;
}

std::unique_ptr<vehicle_agent::AgentPipeline> MakePipeline(const Recording& r) {
  vehicle_agent::AgentPipelineOptions options;
  options.scanner_in_base = r.mount;
  options.localizer.initial_pose_in_map = r.start;
  options.localizer.initial_sigma_xy_m = 0.05;
  options.localizer.initial_sigma_theta_rad = 0.02;
  auto pipeline = std::make_unique<vehicle_agent::AgentPipeline>(options);
  (void)pipeline->SetMap(r.map, 1);
  return pipeline;
}

// Per scan over the whole run, the change included (a temporary map is built for part of it).
void BM_AgentPipeline(benchmark::State& state) {
  const Recording& r = Recorded();
  auto pipeline = MakePipeline(r);
  size_t i = 0;
  for (auto _ : state) {
    if (i == r.scans.size()) {
      state.PauseTiming();
      pipeline = MakePipeline(r);
      i = 0;
      state.ResumeTiming();
    }
    pipeline->AddOdometry(r.odometry[i]);
    benchmark::DoNotOptimize(pipeline->AddScan(r.scans[i]));
    ++i;
  }
}
BENCHMARK(BM_AgentPipeline)->Unit(benchmark::kMicrosecond);

double StatusMegabytes(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::stod(line.substr(std::string(key).size())) / 1024.0;
  return 0.0;
}

// Peak resident memory of the process while the pipeline runs over the recording: the
// kernel's high-water mark is reset after recording (clear_refs 5), so the simulator that
// made the recording does not count; the recording itself (about 3 MB of scans) does.
void RecordPeakMemory() {
  const Recording& r = Recorded();
  std::ofstream("/proc/self/clear_refs") << "5";
  const double before = StatusMegabytes("VmHWM:");
  {
    auto pipeline = MakePipeline(r);
    for (size_t i = 0; i < r.scans.size(); ++i) {
      pipeline->AddOdometry(r.odometry[i]);
      pipeline->AddScan(r.scans[i]);
    }
  }
  RecordFigure("agent.peak_rss_mb", StatusMegabytes("VmHWM:"), "MB");
  RecordFigure("agent.peak_rss_growth_mb", StatusMegabytes("VmHWM:") - before, "MB");
}

}  // namespace
}  // namespace fleetmap::bench

int main(int argc, char** argv) {
  using namespace fleetmap::bench;
  RecordPeakMemory();
  TimeFigure("BM_AgentPipeline", "agent.pipeline_us", "us");
  return RunBenchmarksAndPrintFigures(argc, argv);
}
