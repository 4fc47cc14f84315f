#include "bench/divergence_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "bench/localization_bench_util.h"
#include "core/map/ray_caster.h"
#include "vehicle_agent/divergence.h"
#include "vehicle_agent/localization/localizer.h"

namespace fleetmap::bench {
namespace {

using vehicle_agent::DivergenceDetector;
using vehicle_agent::DivergenceOptions;
using vehicle_agent::DivergenceRule;
using vehicle_agent::Localizer;
using vehicle_agent::LocalizerOptions;

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

}  // namespace

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

}  // namespace fleetmap::bench
