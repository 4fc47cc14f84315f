// The aggregator on the LivingLab map (60 m x 18 m at 5 cm): static-map line extraction (once
// per static map), then per temporary map of typical size (20 m x 20 m at 5 cm, 40 scans of an
// S300 driving 4 m towards a pallet, anchored 0.25 m and 2 degrees off): alignment (line
// extraction of the temporary map, matching, correction, confidence), merge (placement,
// two-phase plan, applying it with its tile delta), and both together. The merge cycles
// through the pallet seen, seen again later (confirmed: added) and seen gone (removed), so
// every merge changes cells. Target: <= 10 ms per temporary map, >= 100 merges per second.
#include <benchmark/benchmark.h>

#include <random>

#include "aggregator/aggregator.h"
#include "aggregator/persistence/journal.h"
#include "bench/figure_reporter.h"
#include "core/map/ray_caster.h"
#include "core/map/scan_inserter.h"
#include "sim/livinglab_map.h"

namespace fleetmap::bench {
namespace {

const core::OccupancyGrid& Hall() {
  static const core::OccupancyGrid hall = sim::MakeLivingLabMap();
  return hall;
}

// A temporary map of `world` from 40 scans along y = 4 m starting at x = 5 m.
core::TempMap MakeTempMap(const core::OccupancyGrid& world, double start_s) {
  core::RayCaster caster(world.geometry());
  std::vector<uint8_t> solid(world.cells().size());
  for (size_t i = 0; i < solid.size(); ++i) solid[i] = world.cells()[i] > 0;
  caster.SetSolid(solid);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.02);
  const core::Pose2 start(5.013, 4.027, 0.0);
  core::TempMap map;
  map.vehicle_id = "cts1";
  map.start_s = start_s;
  map.end_s = start_s + 8.0;
  map.grid = core::OccupancyGrid(core::GridGeometry(0.05, 400, 400, core::Pose2(-2, -10, 0)));
  core::LaserScan scan;
  scan.angle_min_rad = -0.75 * M_PI;
  scan.angle_increment_rad = 0.5 * M_PI / 180;
  scan.range_min_m = 0.05;
  scan.range_max_m = 30.0;
  for (int k = 0; k < 40; ++k) {
    const core::Pose2 in_t(0.1 * k, 0.0, 0.0);
    const core::Pose2 in_map = start * in_t;
    scan.ranges_m.clear();
    for (int i = 0; i < 541; ++i) {
      const auto hit = caster.Cast(in_map.translation(), in_map.theta_rad + scan.angle(i), 30.0);
      scan.ranges_m.push_back(std::isfinite(hit.range_m) ? float(hit.range_m + noise(rng))
                                                         : INFINITY);
    }
    core::InsertScan(scan, in_t, {}, map.grid);
  }
  map.anchor_in_map = core::Pose2(start.x_m + 0.2, start.y_m - 0.15, 2.0 * M_PI / 180);
  return map;
}

// The pallet seen at 0 s, seen again at 20 s, seen gone at 40 s.
const std::vector<core::TempMap>& Cycle() {
  static const std::vector<core::TempMap> maps = [] {
    core::OccupancyGrid with_pallet = Hall();
    sim::AddPalletToMap(with_pallet, 11.0, 6.0);
    return std::vector<core::TempMap>{MakeTempMap(with_pallet, 0.0), MakeTempMap(with_pallet, 20.0),
                                      MakeTempMap(Hall(), 40.0)};
  }();
  return maps;
}

aggregator::Aggregator MakeAggregator() {
  return aggregator::Aggregator::Create(Hall(), {}).value();
}

void BM_StaticLines(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(aggregator::StaticMapFeatures::Compute(Hall(), {}));
}
BENCHMARK(BM_StaticLines)->Unit(benchmark::kMillisecond);

void BM_Align(benchmark::State& state) {
  const aggregator::Aggregator aggregator = MakeAggregator();
  for (auto _ : state) {
    const aggregator::Assessment a = aggregator.Assess(Cycle()[0]);
    if (!a.accepted()) state.SkipWithError(a.reason_text.c_str());
  }
}
BENCHMARK(BM_Align)->Unit(benchmark::kMillisecond);

void BM_Apply(benchmark::State& state) {
  aggregator::Aggregator aggregator = MakeAggregator();
  std::vector<aggregator::Assessment> assessed;
  for (const core::TempMap& m : Cycle()) assessed.push_back(aggregator.Assess(m));
  size_t i = 0, changed = 0;
  for (auto _ : state) {
    const auto r = aggregator.Commit(Cycle()[i], assessed[i], Cycle()[i].end_s);
    if (!r.ok() || !r->accepted) state.SkipWithError("merge failed");
    changed += r.ok() ? size_t(r->cells_added + r->cells_removed + r->candidates_new) : 0;
    i = (i + 1) % Cycle().size();
  }
  state.counters["changed_cells_per_merge"] = double(changed) / double(state.iterations());
}
BENCHMARK(BM_Apply)->Unit(benchmark::kMillisecond);

void BM_DeltaEncode(benchmark::State& state) {
  aggregator::Aggregator aggregator = MakeAggregator();
  for (size_t i = 0; i < 2; ++i) (void)aggregator.Submit(Cycle()[i], Cycle()[i].end_s);
  const uint64_t v = aggregator.store().version();
  for (auto _ : state) benchmark::DoNotOptimize(aggregator.store().DeltaSince(v - 1));
}
BENCHMARK(BM_DeltaEncode)->Unit(benchmark::kMillisecond);

void BM_Total(benchmark::State& state) {
  aggregator::Aggregator aggregator = MakeAggregator();
  size_t i = 0;
  for (auto _ : state) {
    const auto r = aggregator.Submit(Cycle()[i], Cycle()[i].end_s);
    if (!r.ok() || !r->accepted) state.SkipWithError("merge failed");
    i = (i + 1) % Cycle().size();
  }
}
BENCHMARK(BM_Total)->Unit(benchmark::kMillisecond);
// The same again for the rate (the reporter keeps one figure per benchmark).
BENCHMARK(BM_Total)->Name("BM_TotalRate")->Unit(benchmark::kMillisecond);

// What persistence adds: one journal record of a typical merge, written, committed and fsynced.
void BM_JournalAppend(benchmark::State& state) {
  const std::string path = "/tmp/fleetmap_merge_bench_journal.fmj";
  auto writer = aggregator::JournalWriter::Open(path, aggregator::JournalContents{}).value();
  aggregator::MergeCommit commit{1, {"cts1", 1, 0.0, 8.0, 8.0}, {}, {}};
  for (int64_t c = 0; c < 300; ++c)
    commit.changes.push_back({c * 7, aggregator::CellChangeKind::kAdded});
  const std::vector<uint8_t> payload = aggregator::EncodeCommit(commit);
  for (auto _ : state) {
    if (!writer.Append(payload).ok()) state.SkipWithError("append failed");
    if (writer.size_bytes() > (8u << 20)) (void)writer.Reset();
  }
  std::remove(path.c_str());
}
BENCHMARK(BM_JournalAppend)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fleetmap::bench

int main(int argc, char** argv) {
  using namespace fleetmap::bench;
  const auto& features = fleetmap::aggregator::StaticMapFeatures::Compute(Hall(), {}).value();
  RecordFigure("merge.static_lines", double(features.lines().size()), "lines");
  RecordFigure("merge.tempmap_cells", double(Cycle()[0].grid.geometry().num_cells()), "cells");
  TimeFigure("BM_StaticLines", "merge.static_lines_ms", "ms");
  TimeFigure("BM_Align", "merge.align_ms", "ms");
  TimeFigure("BM_Apply", "merge.apply_ms", "ms");
  TimeFigure("BM_DeltaEncode", "merge.delta_ms", "ms");
  TimeFigure("BM_Total", "merge.total_ms", "ms");
  RateFigure("BM_TotalRate", "merge.per_second", "1/s", 1.0);
  TimeFigure("BM_JournalAppend", "merge.journal_fsync_ms", "ms");
  return RunBenchmarksAndPrintFigures(argc, argv);
}
