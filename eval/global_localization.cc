#include "eval/global_localization.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "sim/simulator.h"
#include "vehicle_agent/localization/localizer.h"

namespace fleetmap::eval {

core::Status GlobalLocalizationOptions::Validate() const {
  if (!(starts >= 1 && drive_s > 0 && hold_s >= 0 && tolerance_m > 0 && tolerance_rad > 0 &&
        kidnap_m > 0 && kidnap_rad >= 0))
    return core::InvalidArgument(
        "global localization: starts >= 1, drive_s > 0, hold_s >= 0, tolerances > 0, "
        "kidnap_m > 0, kidnap_rad >= 0");
  return localizer.Validate();
}

double GlobalLocalizationResult::success_share() const {
  if (starts.empty()) return std::numeric_limits<double>::quiet_NaN();
  int ok = 0;
  for (const GlobalStart& s : starts) ok += s.localized;
  return static_cast<double>(ok) / starts.size();
}

namespace {

// One start under way: its localizer and, per scan, whether the estimate was right.
struct Run {
  GlobalStart start;
  std::unique_ptr<vehicle_agent::Localizer> localizer;
  core::OdometrySample odom;
  bool has_odom = false;
  double right_since_s = std::numeric_limits<double>::quiet_NaN();  // NaN: wrong now
  bool started = false;
};

// Start i's kidnapping: off the truth by kidnap_m in a direction that turns by the golden
// angle from start to start, and turned one way or the other.
core::Pose2 KidnappedPose(const core::Pose2& truth, int i, const GlobalLocalizationOptions& o) {
  const double direction = 2.399963 * i;
  return core::Pose2(
      truth.x_m + o.kidnap_m * std::cos(direction), truth.y_m + o.kidnap_m * std::sin(direction),
      core::NormalizeAngle(truth.theta_rad + (i % 2 ? o.kidnap_rad : -o.kidnap_rad)));
}

}  // namespace

core::Result<GlobalLocalizationResult> EvaluateGlobalLocalization(
    const sim::World& world, const GlobalLocalizationOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  const auto& vehicles = world.scenario().vehicles;
  const double window_s = options.drive_s + options.hold_s;
  const double duration_s = world.scenario().duration_s;
  if (vehicles.empty() || duration_s <= window_s)
    return core::InvalidArgument("global localization: the scenario needs vehicles and more than " +
                                 std::to_string(window_s) + " s");
  vehicle_agent::LocalizerOptions localizer = options.localizer;
  const bool kidnapped = options.kind == StartKind::kKidnapped;
  localizer.initial_pose_mode = kidnapped ? vehicle_agent::InitialPoseMode::kFromOptions
                                          : vehicle_agent::InitialPoseMode::kGlobal;
  // Starts: vehicle i mod V, at times spread evenly over what leaves a whole window.
  std::vector<Run> runs(static_cast<size_t>(options.starts));
  const int per_vehicle =
      (options.starts + static_cast<int>(vehicles.size()) - 1) / static_cast<int>(vehicles.size());
  for (int i = 0; i < options.starts; ++i) {
    Run& r = runs[static_cast<size_t>(i)];
    r.start.vehicle = static_cast<size_t>(i) % vehicles.size();
    const int k = i / static_cast<int>(vehicles.size());
    r.start.start_s = (duration_s - window_s) * (k + 0.5) / per_vehicle;
    r.start.time_to_converge_s = std::numeric_limits<double>::quiet_NaN();
    localizer.seed = options.localizer.seed + static_cast<uint32_t>(i);
    r.localizer = std::make_unique<vehicle_agent::Localizer>(localizer);
    FLEETMAP_RETURN_IF_ERROR(r.localizer->SetMap(world.static_map(), 1));
  }
  double last_s = 0.0;  // when the last start's window ends
  for (const Run& r : runs) last_s = std::max(last_s, r.start.start_s + window_s);
  sim::Simulator simulator(&world);
  while (auto event = simulator.Next()) {
    const double t = sim::EventTime(*event);
    if (t > last_s) break;
    if (const auto* o = std::get_if<sim::OdometryEvent>(&*event)) {
      for (Run& r : runs) {
        if (r.start.vehicle != o->vehicle) continue;
        r.odom = {o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps};
        r.has_odom = true;
      }
      continue;
    }
    const auto* scan = std::get_if<sim::ScanEvent>(&*event);
    if (!scan) continue;
    for (Run& r : runs) {
      const double since = scan->scan.stamp_s - r.start.start_s;
      if (r.start.vehicle != scan->vehicle || since < 0 || since > window_s || !r.has_odom)
        continue;
      if (kidnapped && !r.started) {  // sure of a wrong pose: 5 cm and 1 degree
        const Eigen::Matrix3d sure = Eigen::Vector3d(0.05, 0.05, 0.0175).cwiseAbs2().asDiagonal();
        FLEETMAP_RETURN_IF_ERROR(r.localizer->InitializeAt(
            KidnappedPose(scan->true_base_pose, static_cast<int>(&r - runs.data()), options),
            sure));
      }
      r.started = true;
      const auto result =
          r.localizer->Update(r.odom, scan->scan, vehicles[scan->vehicle].scanner_mount);
      const core::Pose2 e = core::Between(scan->true_base_pose, result.estimate.pose_in_map);
      r.start.final_error_m = std::hypot(e.x_m, e.y_m);
      const bool right = r.start.final_error_m <= options.tolerance_m &&
                         std::abs(e.theta_rad) <= options.tolerance_rad;
      if (!right) r.right_since_s = std::numeric_limits<double>::quiet_NaN();
      if (right && std::isnan(r.right_since_s)) r.right_since_s = since;
    }
  }
  GlobalLocalizationResult out;
  out.kind = options.kind;
  for (Run& r : runs) {
    r.start.time_to_converge_s = r.right_since_s;
    r.start.localized = !std::isnan(r.right_since_s) && r.right_since_s <= options.drive_s;
    out.starts.push_back(r.start);
  }
  return out;
}

core::Result<std::string> GlobalLocalizationFigureLines(const GlobalLocalizationResult& result) {
  if (result.starts.empty()) return core::FailedPrecondition("no global localization start ran");
  std::vector<double> times;
  for (const GlobalStart& s : result.starts)
    if (s.localized) times.push_back(s.time_to_converge_s);
  std::sort(times.begin(), times.end());
  const bool kidnapped = result.kind == StartKind::kKidnapped;
  const char* prefix = kidnapped ? "loc.kidnapped" : "loc.global";
  const char* time = kidnapped ? "time_to_recover_s" : "time_to_converge_s";
  char text[512];
  int n = std::snprintf(text, sizeof(text), "%s.success_share %.4g ratio\n%s.starts %zu count\n",
                        prefix, result.success_share(), prefix, result.starts.size());
  std::string out(text, static_cast<size_t>(n));
  if (!times.empty()) {
    const double median = times.size() % 2
                              ? times[times.size() / 2]
                              : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
    n = std::snprintf(text, sizeof(text), "%s.%s %.4g s\n%s.%s.max %.4g s\n", prefix, time, median,
                      prefix, time, times.back());
    out.append(text, static_cast<size_t>(n));
  }
  return out;
}

}  // namespace fleetmap::eval
