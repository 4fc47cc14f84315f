// The on-board perception's cost per scan of one SICK S300 (541 beams, 25 Hz) driving the
// LivingLab addition route: the scan likelihood used for W_avg, one localizer update, one
// divergence step. The agent's whole pipeline must stay under 1 ms per scan on one core.
//
// `localization_bench --divergence_study` instead replays simulated runs through every
// detector variant and prints the table behind the detector's defaults (divergence_study.h);
// `--localization_study` tracks the paper's route with the localizer's defaults and
// alternatives (localization_study.h, docs/localization.md).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "bench/divergence_study.h"
#include "bench/figure_reporter.h"
#include "bench/localization_bench_util.h"
#include "bench/localization_study.h"
#include "vehicle_agent/divergence.h"
#include "vehicle_agent/localization/localizer.h"

namespace fleetmap::bench {
namespace {

using vehicle_agent::DivergenceDetector;
using vehicle_agent::DivergenceOptions;
using vehicle_agent::Localizer;
using vehicle_agent::LocalizerOptions;

// 120 s of the addition route: the first aisle and the turn at its end.
const std::vector<SensorStep>& Steps() {
  static const std::vector<SensorStep> steps = RecordSensorSteps(Addition(), 0, 120.0);
  return steps;
}

// W_avg of the recorded scans, one per iteration, at the true scanner pose.
void ScoreScans(benchmark::State& state, vehicle_agent::ScanLikelihood& model) {
  model.SetMap(Addition().static_map());
  const std::vector<SensorStep>& steps = Steps();
  size_t i = 0;
  for (auto _ : state) {
    const sim::ScanEvent& s = steps[i++ % steps.size()].scan;
    benchmark::DoNotOptimize(model.MeanBeamLikelihood(s.scan, s.true_scanner_pose));
  }
}

void BM_Likelihood(benchmark::State& state) {  // the beam model: W_avg by default
  ScoreScans(state, *vehicle_agent::MakeBeamModel(LocalizerOptions().beam_model));
}
BENCHMARK(BM_Likelihood)->Unit(benchmark::kMicrosecond);

void BM_LikelihoodField(benchmark::State& state) {
  ScoreScans(state, *vehicle_agent::MakeLikelihoodField(LocalizerOptions().likelihood_field));
}
BENCHMARK(BM_LikelihoodField)->Unit(benchmark::kMicrosecond);

// Localizer::Update per scan, W_avg included. Argument 1: the filter updates at every scan
// (the worst case per scan); 0: the default thresholds (a filter update every 5 cm / 0.05 rad).
void BM_MclUpdate(benchmark::State& state) {
  LocalizerOptions options;
  if (state.range(0) == 1) options.update_min_translation_m = options.update_min_rotation_rad = 0;
  options.initial_pose_in_map = Steps()[0].scan.true_base_pose;
  std::unique_ptr<Localizer> localizer;
  size_t i = 0;
  for (auto _ : state) {
    if (i % Steps().size() == 0) {  // (re)start, converged, outside the timing
      state.PauseTiming();
      localizer = std::make_unique<Localizer>(options);
      (void)localizer->SetMap(Addition().static_map(), 1);
      for (i = 0; i < 50; ++i) localizer->Update(Steps()[i].odom, Steps()[i].scan.scan, Mount());
      state.ResumeTiming();
    }
    const SensorStep& s = Steps()[i++ % Steps().size()];
    benchmark::DoNotOptimize(localizer->Update(s.odom, s.scan.scan, Mount()));
  }
}
BENCHMARK(BM_MclUpdate)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

// The particle count BM_MclUpdate runs with: the mean over the recorded scans.
double MeanParticles() {
  LocalizerOptions options;
  options.initial_pose_in_map = Steps()[0].scan.true_base_pose;
  Localizer localizer(options);
  (void)localizer.SetMap(Addition().static_map(), 1);
  double sum = 0.0;
  for (const SensorStep& s : Steps())
    sum += localizer.Update(s.odom, s.scan.scan, Mount()).stats.particles;
  return sum / static_cast<double>(Steps().size());
}

// A building of width x height cells at 5 cm: walls and rack rows 1.2 m deep every 4.2 m.
core::OccupancyGrid RackedHall(int width, int height) {
  core::OccupancyGrid g(core::GridGeometry(0.05, width, height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool wall = x < 4 || y < 4 || x >= width - 4 || y >= height - 4;
      const bool rack = y % 84 >= 60 && x >= 100 && x < width - 100 && x % 600 >= 80;
      g.SetState({x, y}, wall || rack ? core::CellState::kOccupied : core::CellState::kFree);
    }
  return g;
}

// A new map version on a building of 12M cells (argument 1 = 0: 200 x 150 m) or 44M cells (1:
// 400 x 275 m), with a pallet (1.2 x 0.8 m) put down or taken away in its middle: argument 0 =
// 0 takes the whole map in afresh (SetMap), 1 only around the pallet's tile (UpdateMap, as the
// agent does with a delta).
void BM_MapSwap(benchmark::State& state) {
  static const core::OccupancyGrid halls[] = {RackedHall(4000, 3000), RackedHall(8000, 5500)};
  const core::OccupancyGrid& hall = halls[state.range(1)];
  core::OccupancyGrid pallet = hall;
  const int cx = hall.geometry().width() / 2 / 64 * 64, cy = hall.geometry().height() / 2 / 64 * 64;
  const core::CellWindow tile{cx, cy, 64, 64};
  for (int y = cy + 18; y < cy + 34; ++y)
    for (int x = cx + 6; x < cx + 30; ++x) pallet.SetState({x, y}, core::CellState::kOccupied);
  Localizer localizer{LocalizerOptions()};
  (void)localizer.SetMap(hall, 1);
  int32_t version = 1;
  for (auto _ : state) {
    const core::OccupancyGrid& map = ++version % 2 ? hall : pallet;
    benchmark::DoNotOptimize(state.range(0) == 1 ? localizer.UpdateMap(map, version, tile)
                                                 : localizer.SetMap(map, version));
  }
}
BENCHMARK(BM_MapSwap)->Args({0, 0})->Args({1, 0})->Args({1, 1})->Unit(benchmark::kMillisecond);

void BM_Divergence(benchmark::State& state) {
  DivergenceDetector detector{DivergenceOptions()};
  double t = 0.0;
  for (auto _ : state) {
    t += 0.04;
    benchmark::DoNotOptimize(detector.Update(t, 1.0 + 0.1 * std::sin(t), 0.0));
  }
}
BENCHMARK(BM_Divergence)->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace fleetmap::bench

int main(int argc, char** argv) {
  using namespace fleetmap::bench;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--divergence_study") == 0) return RunDivergenceStudy();
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--localization_study") == 0) return RunLocalizationStudy();
  RecordFigure("agent.mcl_particles", MeanParticles(), "particles");
  TimeFigure("BM_Likelihood", "agent.likelihood_us", "us");
  TimeFigure("BM_LikelihoodField", "agent.likelihood_field_us", "us");
  TimeFigure("BM_MclUpdate/1", "agent.mcl_update_us", "us");
  TimeFigure("BM_MclUpdate/0", "agent.mcl_update_default_us", "us");
  TimeFigure("BM_Divergence", "agent.divergence_us", "us");
  TimeFigure("BM_MapSwap/0/0", "agent.map_swap_whole_12m_cells_ms", "ms");
  TimeFigure("BM_MapSwap/1/0", "agent.map_swap_delta_12m_cells_ms", "ms");
  TimeFigure("BM_MapSwap/1/1", "agent.map_swap_delta_44m_cells_ms", "ms");
  return RunBenchmarksAndPrintFigures(argc, argv);
}
