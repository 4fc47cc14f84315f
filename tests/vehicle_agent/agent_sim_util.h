// Runs one simulated vehicle through the localizer and the divergence detector, scan by scan,
// the way the agent pipeline wires them, and keeps what the tests check.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/simulator.h"
#include "vehicle_agent/divergence.h"
#include "vehicle_agent/localization/localizer.h"

namespace fleetmap::vehicle_agent::sim_testing {

inline std::string LivingLabDir() {
  return std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/";
}

inline sim::World LoadWorld(const std::string& scenario_file) {
  auto world = sim::World::Load(LivingLabDir() + scenario_file);
  if (!world.ok()) throw std::runtime_error(world.status().ToString());
  return std::move(world).value();
}

// A scenario on the LivingLab map, written inline.
inline sim::World MakeWorld(const std::string& yaml) {
  auto scenario = sim::ParseScenario(yaml, "inline.yaml");
  if (!scenario.ok()) throw std::runtime_error(scenario.status().ToString());
  auto map = sim::World::Load(LivingLabDir() + "addition.yaml");
  if (!map.ok()) throw std::runtime_error(map.status().ToString());
  auto world = sim::World::Create(std::move(scenario).value(), map->static_map());
  if (!world.ok()) throw std::runtime_error(world.status().ToString());
  return std::move(world).value();
}

struct ScanRecord {
  double stamp_s = 0.0;
  core::Pose2 truth;  // true base pose
  core::PoseEstimate estimate;
  LocalizerStats stats;
  DivergenceSample divergence;
  double omega_radps = 0.0;
};

struct RunOptions {
  size_t vehicle = 0;
  double end_s = 1e9;          // stop the run after this simulated time
  core::Pose2 initial_offset;  // applied to the true start pose (base frame)
  LocalizerOptions localizer;  // initial pose filled in by the runner
  DivergenceOptions divergence;
  // Called before every scan is processed (swap maps, re-initialise, ...).
  std::function<void(double t_s, Localizer&)> before_scan;
  // May damage the inputs of every scan before the localizer sees them.
  std::function<void(core::OdometrySample&, core::LaserScan&)> corrupt;
  // External poses from the simulator (the scenario's external_pose) go to the localizer
  // until this time.
  double external_poses_until_s = -1.0;
  // Scans stamped in [gap_from_s, gap_to_s) never reach the localizer (an agent that stalled),
  // while every odometry sample in the gap does, through AddOdometry, as the agent feeds them.
  double gap_from_s = -1.0, gap_to_s = -1.0;
  // The localizer sees its first scan at this time (a vehicle switched on mid-route).
  double start_s = 0.0;
};

struct SimRun {
  std::vector<ScanRecord> scans;
  LocalizerCounters counters;
  DivergenceStats divergence;
  std::vector<sim::ObjectChangeSeen> seen;  // per object, by this vehicle
};

inline SimRun RunVehicle(const sim::World& world, RunOptions options) {
  const size_t v = options.vehicle;
  const core::Pose2 start = world.VehicleStateAt(v, 0.0).pose;
  options.localizer.initial_pose_in_map = start * options.initial_offset;
  Localizer localizer(options.localizer);
  if (!localizer.SetMap(world.static_map(), 1).ok()) throw std::runtime_error("SetMap failed");
  DivergenceDetector detector(options.divergence);
  const core::Pose2 mount = world.scenario().vehicles[v].scanner_mount;
  sim::Simulator simulator(&world);
  core::OdometrySample odom;
  SimRun run;
  while (auto event = simulator.Next()) {
    if (sim::EventTime(*event) > options.end_s) break;
    if (const auto* o = std::get_if<sim::OdometryEvent>(&*event); o && o->vehicle == v) {
      odom = {o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps};
      if (o->stamp_s >= options.gap_from_s && o->stamp_s < options.gap_to_s)
        localizer.AddOdometry(odom);
      continue;
    }
    if (const auto* x = std::get_if<sim::ExternalPoseEvent>(&*event); x && x->vehicle == v) {
      if (x->stamp_s <= options.external_poses_until_s) {
        core::PoseEstimate pose;
        pose.stamp_s = x->stamp_s;
        pose.pose_in_map = x->pose;
        (void)localizer.AddExternalPose(pose);  // zero covariance: the options' sigmas
      }
      continue;
    }
    const auto* scan = std::get_if<sim::ScanEvent>(&*event);
    if (!scan || scan->vehicle != v) continue;
    if (scan->scan.stamp_s >= options.gap_from_s && scan->scan.stamp_s < options.gap_to_s) continue;
    if (scan->scan.stamp_s < options.start_s) continue;
    if (options.before_scan) options.before_scan(scan->scan.stamp_s, localizer);
    ScanRecord r;
    r.stamp_s = scan->scan.stamp_s;
    r.truth = scan->true_base_pose;
    core::OdometrySample odom_in = odom;
    core::LaserScan scan_in = scan->scan;
    if (options.corrupt) options.corrupt(odom_in, scan_in);
    const LocalizerResult result = localizer.Update(odom_in, scan_in, mount);
    r.estimate = result.estimate;
    r.stats = result.stats;
    r.omega_radps = odom.omega_radps;
    r.divergence = detector.Update(scan_in.stamp_s, result.stats.w_avg, odom_in.omega_radps);
    run.scans.push_back(r);
  }
  run.counters = localizer.counters();
  run.divergence = detector.stats();
  for (size_t k = 0; k < world.scenario().objects.size(); ++k)
    run.seen.push_back(simulator.observations().Seen(k, v));
  return run;
}

inline double TranslationError(const ScanRecord& r) {
  return std::hypot(r.estimate.pose_in_map.x_m - r.truth.x_m,
                    r.estimate.pose_in_map.y_m - r.truth.y_m);
}

inline double HeadingErrorRad(const ScanRecord& r) {
  return std::abs(core::NormalizeAngle(r.estimate.pose_in_map.theta_rad - r.truth.theta_rad));
}

inline double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

inline double Max(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

// Errors of the scans in [from_s, to_s).
inline std::vector<double> Errors(const SimRun& run, double from_s, double to_s,
                                  double (*error)(const ScanRecord&)) {
  std::vector<double> out;
  for (const ScanRecord& r : run.scans)
    if (r.stamp_s >= from_s && r.stamp_s < to_s) out.push_back(error(r));
  return out;
}

// Stamps of the scans at which the detector opened a temporary map.
inline std::vector<double> Starts(const SimRun& run) {
  std::vector<double> out;
  for (const ScanRecord& r : run.scans)
    if (r.divergence.started) out.push_back(r.stamp_s);
  return out;
}

}  // namespace fleetmap::vehicle_agent::sim_testing
