// How well a vehicle finds itself on a known map without a pose (global localization,
// vehicle_agent/localization/global_search.h), or when it was carried off (the kidnapped robot: it
// holds a confident pose kidnap_m away from the truth): at start poses spread over the scenario's
// routes and times, each localizer from its first scan on; a start succeeds when the
// estimate comes within tolerance within `drive_s` and stays there for `hold_s` more. One
// pass of the simulator serves every start.
#pragma once

#include <vector>

#include "sim/world.h"
#include "vehicle_agent/localization/localizer_options.h"

namespace fleetmap::eval {

enum class StartKind {
  kNoPose,     // switched on without a pose: global localization (loc.global.*)
  kKidnapped,  // sure of a pose kidnap_m and kidnap_rad off the truth (loc.kidnapped.*)
};

struct GlobalLocalizationOptions {
  StartKind kind = StartKind::kNoPose;
  double kidnap_m = 5.0;          // kKidnapped: the believed pose this far off, m, > 0 ...
  double kidnap_rad = 0.5;        // ... and turned by this, rad, >= 0
  int starts = 20;                // start poses, spread over the vehicles and their routes, >= 1
  double drive_s = 10.0;          // allowed until the pose is right, s, > 0
  double hold_s = 5.0;            // ... and it must stay right this long after, s, >= 0
  double tolerance_m = 0.2;       // right: within this distance ...
  double tolerance_rad = 0.0524;  // ... and heading (3 degrees)
  vehicle_agent::LocalizerOptions localizer;  // initial_pose_mode is set to kGlobal
  core::Status Validate() const;
};

struct GlobalStart {
  size_t vehicle = 0;
  double start_s = 0.0;
  bool localized = false;
  double time_to_converge_s = 0.0;  // first scan from which it stays right; NaN: never
  double final_error_m = 0.0;       // at the end of the start's window
};

struct GlobalLocalizationResult {
  StartKind kind = StartKind::kNoPose;
  std::vector<GlobalStart> starts;
  double success_share() const;  // NaN without a start
};

// InvalidArgument when the scenario is too short for one start's window.
core::Result<GlobalLocalizationResult> EvaluateGlobalLocalization(
    const sim::World& world, const GlobalLocalizationOptions& options);

// `loc.global.*` figure lines: success_share (ratio), time_to_converge_s (median over the
// starts that localized; also .max), starts (count); for kidnapped starts `loc.kidnapped.*`
// with time_to_recover_s. An error when nothing was measured.
core::Result<std::string> GlobalLocalizationFigureLines(const GlobalLocalizationResult& result);

}  // namespace fleetmap::eval
