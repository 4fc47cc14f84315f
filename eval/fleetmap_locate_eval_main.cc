// fleetmap-locate-eval: global localization on a scenario's world, scored against the
// simulator's truth (eval/global_localization.h): vehicles switched on without a pose
// at start poses spread over their routes (loc.global.*), and vehicles kidnapped there, sure
// of a pose metres off (loc.kidnapped.*).
#include <cmath>
#include <cstdio>
#include <string>

#include "core/command_line.h"
#include "eval/global_localization.h"
#include "sim/world.h"

namespace {

using namespace fleetmap;

// One kind of start: its figure lines on stdout; false (said on stderr) when not measured.
bool Measure(const sim::World& world, const eval::GlobalLocalizationOptions& o, bool per_start) {
  auto result = eval::EvaluateGlobalLocalization(world, o);
  if (!result.ok()) {
    std::fprintf(stderr, "fleetmap-locate-eval: %s\n", result.status().ToString().c_str());
    return false;
  }
  if (per_start) {
    for (const eval::GlobalStart& s : result->starts) {
      std::fprintf(stderr, "%s: vehicle %zu at %.1f s: %s, right from %.1f s, final error %.3f m\n",
                   o.kind == eval::StartKind::kKidnapped ? "kidnapped" : "no pose", s.vehicle,
                   s.start_s, s.localized ? "localized" : "NOT localized", s.time_to_converge_s,
                   s.final_error_m);
    }
  }
  auto lines = eval::GlobalLocalizationFigureLines(*result);
  if (!lines.ok()) {
    std::fprintf(stderr, "fleetmap-locate-eval: %s\n", lines.status().ToString().c_str());
    return false;
  }
  std::printf("%s", lines->c_str());
  std::fflush(stdout);
  return true;
}

int Run(int argc, char** argv) {
  CLI::App app(
      "Global localization on a scenario's world: vehicles switched on without a pose at start\n"
      "poses spread over the vehicles' routes and times; each start succeeds when its pose is\n"
      "within the tolerance within --drive-s and stays so for --hold-s. Prints\n"
      "loc.global.success_share, loc.global.time_to_converge_s (median of the successful\n"
      "starts, and .max) and loc.global.starts as `name value unit` lines. Then the same\n"
      "starts kidnapped: each vehicle sure of a pose --kidnap-m away and --kidnap-rad turned\n"
      "must find itself within --recover-s: loc.kidnapped.success_share,\n"
      "loc.kidnapped.time_to_recover_s (and .max), loc.kidnapped.starts.\n"
      "Exit status: 0 measured, 1 the world cannot be loaded or measured, 2 usage errors.",
      "fleetmap-locate-eval");
  core::AddVersionFlag(app);
  std::string scenario, map;
  eval::GlobalLocalizationOptions o;
  bool per_start = false;
  std::string kinds = "both";
  double recover_s = 15.0;
  app.add_option("--scenario", scenario, "the scenario (docs/scenario.md)")->required();
  app.add_option("--map", map, "a static map instead of the scenario's own");
  app.add_option("--starts", o.starts, "start poses")->capture_default_str();
  app.add_option("--drive-s", o.drive_s, "seconds allowed until the pose is right")
      ->capture_default_str();
  app.add_option("--hold-s", o.hold_s, "seconds it must stay right after")->capture_default_str();
  app.add_option("--tolerance-m", o.tolerance_m, "right: within this many metres")
      ->capture_default_str();
  app.add_option("--kind", kinds, "which starts: global, kidnapped or both")
      ->check(CLI::IsMember({"global", "kidnapped", "both"}))
      ->capture_default_str();
  app.add_option("--recover-s", recover_s, "kidnapped: seconds allowed until the pose is right")
      ->capture_default_str();
  app.add_option("--kidnap-m", o.kidnap_m, "kidnapped: metres between belief and truth")
      ->capture_default_str();
  app.add_option("--kidnap-rad", o.kidnap_rad, "kidnapped: heading between belief and truth")
      ->capture_default_str();
  app.add_flag("--per-start", per_start, "also one line per start on stderr");
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  if (!(recover_s > 0)) {
    std::fprintf(stderr, "fleetmap-locate-eval: --recover-s must be > 0\n");
    return 2;
  }
  if (const core::Status valid = o.Validate(); !valid.ok()) {
    std::fprintf(stderr, "fleetmap-locate-eval: %s\n", valid.ToString().c_str());
    return 2;
  }
  auto world = sim::World::Load(scenario, map);
  if (!world.ok()) {
    std::fprintf(stderr, "fleetmap-locate-eval: %s\n", world.status().ToString().c_str());
    return 1;
  }
  for (const eval::StartKind kind : {eval::StartKind::kNoPose, eval::StartKind::kKidnapped}) {
    const bool kidnapped = kind == eval::StartKind::kKidnapped;
    if (kinds != "both" && kidnapped != (kinds == "kidnapped")) continue;
    eval::GlobalLocalizationOptions run = o;
    run.kind = kind;
    if (kidnapped) run.drive_s = recover_s;
    if (!Measure(*world, run, per_start)) return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return Run(argc, argv); }
