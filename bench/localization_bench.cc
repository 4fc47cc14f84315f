// The on-board perception's cost per scan of one SICK S300 (541 beams, 25 Hz) driving the
// LivingLab addition route: the scan likelihood used for W_avg, one localizer update, one
// divergence step. The agent's whole pipeline must stay under 1 ms per scan on one core.
//
// `localization_bench --divergence_study` instead replays simulated runs through every
// detector variant and prints the table behind the detector's defaults; `--localization_study`
// tracks the paper's route with the localizer's defaults and alternatives (docs/localization.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench/figure_reporter.h"
#include "core/map/ray_caster.h"
#include "sim/simulator.h"
#include "vehicle_agent/divergence.h"
#include "vehicle_agent/localization/localizer.h"

namespace fleetmap::bench {
namespace {

using vehicle_agent::DivergenceDetector;
using vehicle_agent::DivergenceOptions;
using vehicle_agent::DivergenceRule;
using vehicle_agent::Localizer;
using vehicle_agent::LocalizerOptions;

std::string WorldsDir() { return std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/"; }

sim::World OrDie(core::Result<sim::World> world) {
  if (!world.ok()) {
    std::fprintf(stderr, "localization_bench: %s\n", world.status().ToString().c_str());
    std::exit(1);
  }
  return std::move(world).value();
}

sim::World LoadWorld(const std::string& scenario_file) {
  return OrDie(sim::World::Load(WorldsDir() + scenario_file));
}

// A scenario written inline, on the LivingLab map.
sim::World ParseWorld(const std::string& yaml) {
  auto scenario = sim::ParseScenario(yaml, "study.yaml");
  if (!scenario.ok()) return OrDie(scenario.status());
  return OrDie(
      sim::World::Create(std::move(scenario).value(), LoadWorld("addition.yaml").static_map()));
}

// What one vehicle's sensors reported, scan by scan, with the odometry sample before it.
struct SensorStep {
  core::OdometrySample odom;
  sim::ScanEvent scan;
};

std::vector<SensorStep> Record(const sim::World& world, size_t vehicle, double end_s) {
  sim::Simulator simulator(&world);
  std::vector<SensorStep> steps;
  core::OdometrySample odom;
  while (auto e = simulator.Next()) {
    if (sim::EventTime(*e) > end_s) break;
    if (const auto* o = std::get_if<sim::OdometryEvent>(&*e); o && o->vehicle == vehicle)
      odom = {o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps};
    if (const auto* s = std::get_if<sim::ScanEvent>(&*e); s && s->vehicle == vehicle)
      steps.push_back({odom, *s});
  }
  return steps;
}

const sim::World& Addition() {
  static const sim::World world = LoadWorld("addition.yaml");
  return world;
}

// 120 s of the addition route: the first aisle and the turn at its end.
const std::vector<SensorStep>& Steps() {
  static const std::vector<SensorStep> steps = Record(Addition(), 0, 120.0);
  return steps;
}

const core::Pose2& Mount() { return Addition().scenario().vehicles[0].scanner_mount; }

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

// ---------------------------------------------------------------------------------------
// The localization study: tracking on the paper's five-minute route, started 0.5 m and
// 10 deg off, for the defaults and the alternatives they were chosen over.

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void Track(const std::string& name, const std::vector<SensorStep>& steps, LocalizerOptions o) {
  o.initial_pose_in_map = steps[0].scan.true_base_pose * core::Pose2(0.4, -0.3, 10 * M_PI / 180);
  Localizer localizer(o);
  (void)localizer.SetMap(Addition().static_map(), 1);
  std::vector<double> error_m, error_deg, converging_m;
  double particles = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (const SensorStep& s : steps) {
    const auto r = localizer.Update(s.odom, s.scan.scan, Mount());
    particles += r.stats.particles;
    const core::Pose2 e = core::Between(s.scan.true_base_pose, r.estimate.pose_in_map);
    if (s.scan.scan.stamp_s < 10.0) {
      converging_m.push_back(std::hypot(e.x_m, e.y_m));
      continue;
    }
    error_m.push_back(std::hypot(e.x_m, e.y_m));
    error_deg.push_back(std::abs(e.theta_rad) * 180 / M_PI);
  }
  const std::chrono::duration<double, std::micro> us = std::chrono::steady_clock::now() - start;
  const double n = static_cast<double>(steps.size());
  std::printf("%-22s %8.4f %9.4f %8.4f %8.3f %8.2f %9.0f %8ld %8.1f\n", name.c_str(),
              Median(converging_m), Median(error_m),
              *std::max_element(error_m.begin(), error_m.end()), Median(error_deg),
              *std::max_element(error_deg.begin(), error_deg.end()), particles / n,
              static_cast<long>(localizer.counters().filter_updates), us.count() / n);
}

int RunLocalizationStudy() {
  const std::vector<SensorStep> steps = Record(Addition(), 0, 300.0);
  std::printf("%-22s %8s %9s %8s %8s %8s %9s %8s %8s\n", "variant", "0-10s_m", "median_m", "max_m",
              "med_deg", "max_deg", "particles", "updates", "us/scan");
  const LocalizerOptions d;
  auto with = [&d](auto change) {
    LocalizerOptions o = d;
    change(o);
    return o;
  };
  Track("default", steps, d);
  Track("sigma_hit_0.2_amcl", steps, with([](auto& o) { o.likelihood_field.sigma_hit_m = 0.2; }));
  Track("sigma_hit_0.05", steps, with([](auto& o) { o.likelihood_field.sigma_hit_m = 0.05; }));
  Track("no_lateral_slip", steps, with([](auto& o) { o.motion.alpha5_lateral_from_trans = 0; }));
  Track("update_every_scan", steps,
        with([](auto& o) { o.update_min_translation_m = o.update_min_rotation_rad = 0; }));
  Track("update_0.2m_30deg_amcl", steps, with([](auto& o) {
          o.update_min_translation_m = 0.2, o.update_min_rotation_rad = M_PI / 6;
        }));
  Track("max_beams_30", steps, with([](auto& o) { o.max_beams = 30; }));
  Track("max_beams_120", steps, with([](auto& o) { o.max_beams = 120; }));
  Track("min_particles_100", steps, with([](auto& o) { o.kld.min_particles = 100; }));
  Track("min_particles_500", steps, with([](auto& o) { o.kld.min_particles = 500; }));
  return 0;
}

void BM_Divergence(benchmark::State& state) {
  DivergenceDetector detector{DivergenceOptions()};
  double t = 0.0;
  for (auto _ : state) {
    t += 0.04;
    benchmark::DoNotOptimize(detector.Update(t, 1.0 + 0.1 * std::sin(t), 0.0));
  }
}
BENCHMARK(BM_Divergence)->Unit(benchmark::kNanosecond);

// ---------------------------------------------------------------------------------------
// The divergence study: W_avg traces of simulated runs, replayed through detector variants.

struct TraceSample {
  double t_s, w_beam, w_field, omega_radps;
  int changed_beams;  // beams whose noise-free range in the true world differs from the map's
};

struct Trace {
  std::string name;
  std::vector<TraceSample> samples;
};

std::vector<uint8_t> Occupied(const core::OccupancyGrid& map) {
  std::vector<uint8_t> solid(map.cells().size());
  const core::TriStateClassifier classify;
  for (size_t i = 0; i < solid.size(); ++i)
    solid[i] = classify(map.cells()[i]) == core::CellState::kOccupied;
  return solid;
}

// Beams of `scan` (every other one) that see a change: the true world's first surface and
// the map's differ by more than 0.3 m. People and forklifts are not changes.
int ChangedBeams(const sim::ScanEvent& s, const core::RayCaster& world,
                 const core::RayCaster& map) {
  int changed = 0;
  const double range = s.scan.range_max_m;
  for (size_t i = 0; i < s.scan.size(); i += 2) {
    const double a = s.true_scanner_pose.theta_rad + s.scan.angle(i);
    const double w =
        std::min(world.Cast(s.true_scanner_pose.translation(), a, range).range_m, range);
    const double m = std::min(map.Cast(s.true_scanner_pose.translation(), a, range).range_m, range);
    changed += std::abs(w - m) > 0.3;
  }
  return 2 * changed;
}

// Runs the localizer on `localizer_map` and records both models' W_avg at its estimate.
Trace MakeTrace(const std::string& name, const sim::World& world, size_t vehicle,
                const core::OccupancyGrid& localizer_map) {
  LocalizerOptions options;
  options.initial_pose_in_map = world.VehicleStateAt(vehicle, 0.0).pose;
  Localizer localizer(options);
  (void)localizer.SetMap(localizer_map, 1);
  vehicle_agent::LikelihoodField field(options.likelihood_field);
  field.SetMap(localizer_map);
  const core::Pose2 mount = world.scenario().vehicles[vehicle].scanner_mount;
  Trace trace{name, {}};
  core::RayCaster map_caster(world.geometry()), world_caster(world.geometry());
  map_caster.SetSolid(Occupied(localizer_map));
  world_caster.SetSolid(world.SolidAt(0.0));
  std::vector<double> change_times = world.ChangeTimes();
  size_t next_change = 0;
  sim::Simulator simulator(&world);
  core::OdometrySample odom;
  while (auto e = simulator.Next()) {
    if (const auto* o = std::get_if<sim::OdometryEvent>(&*e); o && o->vehicle == vehicle)
      odom = {o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps};
    const auto* s = std::get_if<sim::ScanEvent>(&*e);
    if (!s || s->vehicle != vehicle) continue;
    const auto r = localizer.Update(odom, s->scan, mount);
    const double w_field = field.MeanBeamLikelihood(s->scan, r.estimate.pose_in_map * mount);
    bool changed = false;
    while (next_change < change_times.size() && change_times[next_change] <= s->scan.stamp_s)
      ++next_change, changed = true;
    if (changed) world_caster.SetSolid(world.SolidAt(s->scan.stamp_s));
    trace.samples.push_back({s->scan.stamp_s, r.stats.w_avg, w_field, odom.omega_radps,
                             ChangedBeams(*s, world_caster, map_caster)});
  }
  return trace;
}

struct Score {
  int starts = 0, false_starts = 0, episodes = 0, detected = 0;
  double latency_sum_s = 0.0, latency_max_s = 0.0, building_s = 0.0, duration_s = 0.0;
  void Add(const Score& o) {
    starts += o.starts, false_starts += o.false_starts, episodes += o.episodes;
    detected += o.detected, latency_sum_s += o.latency_sum_s;
    latency_max_s = std::max(latency_max_s, o.latency_max_s);
    building_s += o.building_s, duration_s += o.duration_s;
  }
};

// A change is in view while at least kInViewBeams beams see it (a pallet's 0.8 m face at
// 8 m); an episode starts after 2 s without. A start is false when no scan in the 3 s before
// it had kExplainBeams changed beams (people and forklifts do not count).
constexpr int kInViewBeams = 20;
constexpr int kExplainBeams = 6;

std::vector<double> EpisodeStarts(const Trace& trace) {
  std::vector<double> starts;
  double last_in_view = -1e9;
  for (const TraceSample& s : trace.samples) {
    if (s.changed_beams < kInViewBeams) continue;
    if (s.t_s - last_in_view > 2.0) starts.push_back(s.t_s);
    last_in_view = s.t_s;
  }
  return starts;
}

bool Explained(const Trace& trace, double t_s) {
  for (const TraceSample& s : trace.samples)
    if (s.t_s >= t_s - 3.0 && s.t_s <= t_s && s.changed_beams >= kExplainBeams) return true;
  return false;
}

Score Replay(const Trace& trace, const DivergenceOptions& options, bool beam) {
  DivergenceDetector detector(options);
  Score score;
  std::vector<double> building_at;
  for (const TraceSample& s : trace.samples) {
    const auto d = detector.Update(s.t_s, beam ? s.w_beam : s.w_field, s.omega_radps);
    if (d.building) building_at.push_back(s.t_s);
    if (!d.started) continue;
    ++score.starts;
    score.false_starts += !Explained(trace, s.t_s);
  }
  for (double start : EpisodeStarts(trace)) {
    ++score.episodes;
    const auto it = std::lower_bound(building_at.begin(), building_at.end(), start - 1e-6);
    if (it == building_at.end() || *it > start + 10.0) continue;
    ++score.detected;
    score.latency_sum_s += *it - start;
    score.latency_max_s = std::max(score.latency_max_s, *it - start);
  }
  score.building_s = detector.stats().building_s;
  score.duration_s = trace.samples.empty() ? 0.0 : trace.samples.back().t_s;
  return score;
}

// The unchanged hall, no objects: the addition route, and a zigzag turning in place at each
// of its 7 waypoints.
constexpr const char* kEmptyHall = R"(
name: empty_hall
map: livinglab.yaml
duration_s: 300
seed: 11
vehicles:
  - id: loop
    route: [[5.0, 4.0], [55.0, 4.0], [55.0, 13.5], [5.0, 13.5]]
    loop: true
  - id: zigzag
    route: [[6, 3], [14, 7], [22, 3], [30, 7], [38, 3], [46, 7], [54, 3]]
    loop: true
)";

// Pallets appearing in the vehicle's view while it drives the loop.
constexpr const char* kAppearing = R"(
name: appearing
map: livinglab.yaml
duration_s: 300
seed: 12
objects:
  - {id: a, rect: {center: [25.0, 5.6], size: [1.2, 0.8]}, appear_s: 20}
  - {id: b, rect: {center: [45.0, 2.3], size: [1.2, 0.8]}, appear_s: 60}
  - {id: c, rect: {center: [30.0, 12.0], size: [0.8, 1.2]}, appear_s: 150}
  - {id: d, rect: {center: [15.0, 15.0], size: [1.2, 0.8]}, appear_s: 200}
vehicles:
  - id: v
    route: [[5.0, 4.0], [55.0, 4.0], [55.0, 13.5], [5.0, 13.5]]
    loop: true
)";

std::vector<Trace> StudyTraces() {
  std::vector<Trace> traces;
  const sim::World hall = ParseWorld(kEmptyHall);
  traces.push_back(MakeTrace("hall_loop", hall, 0, hall.static_map()));
  traces.push_back(MakeTrace("hall_zigzag", hall, 1, hall.static_map()));
  const sim::World appearing = ParseWorld(kAppearing);
  traces.push_back(MakeTrace("appearing", appearing, 0, appearing.static_map()));
  const sim::World addition = LoadWorld("addition.yaml");
  traces.push_back(MakeTrace("addition", addition, 0, addition.static_map()));
  // Removal, with the pallets already merged into the vehicle's map.
  const sim::World removal = LoadWorld("removal.yaml");
  traces.push_back(MakeTrace("removal", removal, 0, removal.TrueMapAt(0.0)));
  const sim::World fleet = LoadWorld("fleet.yaml");
  for (size_t v = 0; v < fleet.scenario().vehicles.size(); ++v)
    traces.push_back(MakeTrace("fleet_" + std::to_string(v), fleet, v, fleet.static_map()));
  return traces;
}

struct Variant {
  std::string name;
  DivergenceOptions options;
  bool beam = true;
};

std::vector<Variant> StudyVariants() {
  DivergenceOptions paper, d;  // d: the defaults
  paper.rule = DivergenceRule::kPaper;
  std::vector<Variant> v = {{"paper", paper}, {"paper_field", paper, false}};
  v.push_back({"paper_no_freeze", paper}), v.back().options.rotation_freeze_radps = 1e9;
  v.push_back({"paper_cold", paper}), v.back().options.warm_up = false;
  for (double start : {0.05, 0.08, 0.1, 0.15, 0.2}) {
    v.push_back({"hyst_" + std::to_string(start).substr(0, 4), d});
    v.back().options.start_above = start;
    v.back().options.stop_below = std::min(d.stop_below, start / 2);
  }
  v.push_back({"default", d});
  v.push_back({"default_field", d, false});
  v.push_back({"default_no_freeze", d}), v.back().options.rotation_freeze_radps = 1e9;
  v.push_back({"default_cold", d}), v.back().options.warm_up = false;
  v.push_back({"default_slow_0.0003", d}), v.back().options.alpha_slow = 0.0003;
  v.push_back({"default_fast_0.2", d}), v.back().options.alpha_fast = 0.2;
  v.push_back({"default_min_0s", d}), v.back().options.min_duration_s = 0.0;
  return v;
}

void PrintRow(const std::string& variant, const std::string& trace, const Score& s) {
  std::printf("%-20s %-12s %6d %6d %4d/%-4d %8.2f %8.2f %8.0f%%\n", variant.c_str(), trace.c_str(),
              s.starts, s.false_starts, s.detected, s.episodes,
              s.detected ? s.latency_sum_s / s.detected : std::nan(""), s.latency_max_s,
              100.0 * s.building_s / std::max(s.duration_s, 1e-9));
}

int RunDivergenceStudy() {
  const std::vector<Trace> traces = StudyTraces();
  std::printf("%-20s %-12s %6s %6s %9s %8s %8s %9s\n", "variant", "trace", "starts", "false",
              "in view", "lat_avg", "lat_max", "building");
  for (const Variant& v : StudyVariants()) {
    Score total;
    for (const Trace& t : traces) {
      const Score s = Replay(t, v.options, v.beam);
      total.Add(s);
      PrintRow(v.name, t.name, s);
    }
    PrintRow(v.name, "TOTAL", total);
    std::printf("\n");
  }
  return 0;
}

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
  return RunBenchmarksAndPrintFigures(argc, argv);
}
