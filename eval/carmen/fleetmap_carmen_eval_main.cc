// fleetmap-carmen-eval: runs the temporary-map builder's scan matcher over a CARMEN log and
// scores its trajectory with the SLAM benchmark's relations, next to the log's odometry.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/command_line.h"
#include "core/image/map_render.h"
#include "core/map/scan_inserter.h"
#include "eval/carmen/carmen_log.h"
#include "eval/carmen/relation_audit.h"
#include "eval/carmen/relations.h"
#include "vehicle_agent/mapping/local_mapper.h"

namespace {

using namespace fleetmap;

constexpr char kDescription[] =
    R"(Runs the scan matcher of the temporary-map builder over every laser scan of a CARMEN log
(FLASER, ROBOTLASER1), with the log's odometry as the prior, and scores the trajectory with the
benchmark relations (Kuemmerle et al. 2009): mean absolute translational and rotational error
over all relations and over those spanning at most --window seconds. The log's raw odometry is
scored the same way as the baseline. Prints `real.<name>.<...> value unit` lines.)";

struct Args {
  std::string carmen, relations, name, png, trajectory, save_trajectory;
  double window_s = 60, lifetime_s = 0, size_m = 120, resolution_m = 0.05;
  int levels = 3;
  bool interpolate_odometry = false, audit = false;
  double scan_latency_s = 0;
  vehicle_agent::LocalMapperOptions mapper;  // matcher and update settings
};

// A number flag with its default shown in --help.
CLI::Option* Number(CLI::App& app, const std::string& name, double& value,
                    const std::string& help) {
  return app.add_option(name, value, help)->check(core::Finite())->capture_default_str();
}

void DefineFlags(CLI::App& app, Args& a) {
  app.description(kDescription);
  core::AddVersionFlag(app);
  app.add_option("--carmen", a.carmen, "the CARMEN log")->required()->type_name("LOG");
  app.add_option("--relations", a.relations, "the benchmark's relations")
      ->required()
      ->type_name("REL");
  app.add_option("--name", a.name, "name in the figure lines [the log's file stem]");
  Number(app, "--window", a.window_s, "span of the windowed figures, seconds")
      ->check(core::Positive());
  Number(app, "--map-lifetime", a.lifetime_s,
         "start a fresh map every S seconds, chained like temporary maps; 0: one map for the "
         "whole log")
      ->check(core::NotNegative());
  Number(app, "--map-size", a.size_m, "side of each map, metres");
  Number(app, "--resolution", a.resolution_m, "finest cell size, metres");
  app.add_option("--levels", a.levels, "resolution levels")->capture_default_str();
  app.add_option("--png", a.png, "draw the log's map at the estimated poses")->type_name("FILE");
  app.add_option("--trajectory", a.trajectory,
                 "score the trajectory in FILE (lines `t x y theta`, e.g. another SLAM "
                 "system's) with the same relations instead of running our matcher; with --png, "
                 "FILE must hold one pose per scan")
      ->type_name("FILE");
  app.add_option("--save-trajectory", a.save_trajectory,
                 "write our estimated pose at every scan to FILE, in the lines --trajectory "
                 "reads")
      ->type_name("FILE");
  app.add_option("--interpolate-odometry", a.interpolate_odometry,
                 "odometry at each scan's time from the ODOM lines, rather than the last ODOM "
                 "before it (what FLASER lines carry)")
      ->type_name("0|1")
      ->capture_default_str();
  Number(app, "--scan-latency", a.scan_latency_s,
         "each scan was taken S seconds before its time stamp: odometry interpolated at stamp "
         "- S (implies --interpolate-odometry 1)");
  Number(app, "--max-range", a.mapper.max_range_m, "returns farther away are not used");
  Number(app, "--prior-xy", a.mapper.matcher.prior_sigma_xy_m, "odometry prior (base), metres");
  Number(app, "--prior-theta", a.mapper.matcher.prior_sigma_theta_rad,
         "odometry prior (base), radians");
  Number(app, "--sigma-map", a.mapper.matcher.sigma_map, "map noise");
  app.add_option("--coarse-iterations", a.mapper.matcher.coarse_iterations,
                 "Gauss-Newton steps per coarser level")
      ->capture_default_str();
  app.add_option("--fine-iterations", a.mapper.matcher.fine_iterations,
                 "Gauss-Newton steps on the finest level")
      ->capture_default_str();
  Number(app, "--heading-search-base", a.mapper.matcher.heading_search_base_rad,
         "heading searched within +-(RAD + F x odometry rotation) before Gauss-Newton; 0 and "
         "0: no search");
  Number(app, "--heading-search", a.mapper.matcher.heading_search_per_rad,
         "F of --heading-search-base");
  Number(app, "--update-distance", a.mapper.update_min_distance_m,
         "travel between map insertions, metres");
  Number(app, "--update-angle", a.mapper.update_min_angle_rad,
         "turn between map insertions, radians");
  Number(app, "--rest-distance", a.mapper.rest_max_translation_m,
         "odometry steps this small are standing still: the scan is not matched; 0 and 0: "
         "match every scan");
  Number(app, "--rest-angle", a.mapper.rest_max_rotation_rad, "radians of --rest-distance");
  app.add_option("--audit", a.audit,
                 "also check the reference itself, within the window: the share of relations "
                 "equal to the log's odometry (as read) and, of the others, whose difference "
                 "from it is a whole number of 5 cm steps (aces': a search grid's); and how well "
                 "each relation's two scans overlap placed by the reference and by our estimate "
                 "(or --trajectory's): the mean distance of the second scan's end points to the "
                 "first's nearest, capped at 0.2 m")
      ->type_name("0|1")
      ->capture_default_str();
}

std::string Stem(const std::string& path) {
  std::string s = path.substr(path.find_last_of('/') + 1);
  return s.substr(0, s.find('.'));
}

vehicle_agent::LocalMapperOptions MapperOptions(const Args& args) {
  vehicle_agent::LocalMapperOptions options = args.mapper;
  options.map.resolution_m = args.resolution_m;
  options.map.levels = args.levels;
  options.map.size_m = args.size_m;
  return options;
}

std::vector<eval::carmen::TimedPose> RunMatcher(const eval::carmen::CarmenLog& log,
                                                const Args& args, double& ms_per_scan) {
  const vehicle_agent::LocalMapperOptions options = MapperOptions(args);
  std::vector<eval::carmen::TimedPose> trajectory;
  std::unique_ptr<vehicle_agent::LocalMapper> mapper;
  double map_start_s = 0;
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < log.lasers.size(); ++i) {
    const eval::carmen::LaserRecord& r = log.lasers[i];
    const core::Pose2 delta =
        i == 0 ? core::Pose2() : core::Between(log.lasers[i - 1].odom_pose, r.odom_pose);
    if (!mapper || (args.lifetime_s > 0 && r.stamp_s - map_start_s >= args.lifetime_s) ||
        !mapper->map().Inside(mapper->pose().translation(), 10.0)) {
      // A fresh map at the current estimate, as a new temporary map would start.
      const core::Pose2 start_pose = mapper ? mapper->pose() * delta : r.odom_pose;
      mapper = std::make_unique<vehicle_agent::LocalMapper>(options, start_pose);
      map_start_s = r.stamp_s;
      mapper->AddScan(r.scan, {}, r.laser_in_base);
    } else {
      mapper->AddScan(r.scan, delta, r.laser_in_base);
    }
    trajectory.push_back({r.stamp_s, mapper->pose()});
  }
  ms_per_scan =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
      log.lasers.size();
  return trajectory;
}

// Every scan inserted at its estimated pose into one grid covering the whole trajectory.
core::Status DrawMap(const eval::carmen::CarmenLog& log,
                     const std::vector<eval::carmen::TimedPose>& trajectory,
                     const std::string& path) {
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const auto& p : trajectory) {
    lo = lo.cwiseMin(p.pose.translation());
    hi = hi.cwiseMax(p.pose.translation());
  }
  const double res = 0.05, margin = 15.0;
  core::OccupancyGrid grid(core::GridGeometry(res, int((hi.x() - lo.x() + 2 * margin) / res),
                                              int((hi.y() - lo.y() + 2 * margin) / res),
                                              core::Pose2(lo.x() - margin, lo.y() - margin, 0)));
  core::ScanInsertOptions insert;
  insert.max_range_m = 20.0;
  for (size_t i = 0; i < log.lasers.size(); i += 2)
    core::InsertScan(log.lasers[i].scan, trajectory[i].pose * log.lasers[i].laser_in_base, insert,
                     grid);
  return core::RenderGridToPng(grid, path);
}

// Scores `trajectory` by the relations spanning at most `max_span_s` and prints the figures
// real.NAME.WHAT.*; false, with the reason on stderr, when no relation could be scored (a
// mean over nothing is not a figure).
bool Score(const std::string& name, const std::string& what,
           const std::vector<eval::carmen::Relation>& relations,
           const std::vector<eval::carmen::TimedPose>& trajectory,
           double max_span_s = std::numeric_limits<double>::infinity()) {
  const eval::carmen::RelationErrors e =
      eval::carmen::ScoreRelations(relations, trajectory, max_span_s);
  if (const core::Status s = eval::carmen::CheckScored(e, relations, trajectory, max_span_s);
      !s.ok()) {
    std::fprintf(stderr, "fleetmap-carmen-eval: %s: %s\n", what.c_str(), s.ToString().c_str());
    return false;
  }
  std::printf("real.%s.%s.trans_mean_m %.4f m\n", name.c_str(), what.c_str(), e.trans_mean_m);
  std::printf("real.%s.%s.rot_mean_deg %.3f deg\n", name.c_str(), what.c_str(), e.rot_mean_deg);
  std::printf("real.%s.%s.missing_share %.3f fraction\n", name.c_str(), what.c_str(),
              e.missing_share());
  std::fprintf(stderr, "  %-12s %5d relations (%d missing): %.4f +- %.4f m, %.3f +- %.3f deg\n",
               what.c_str(), e.used, e.missing, e.trans_mean_m, e.trans_std_m, e.rot_mean_deg,
               e.rot_std_deg);
  if (e.missing_share() > 0.5)
    std::fprintf(stderr,
                 "  %-12s warning: %d of %d relations have no scan at their time stamps: the "
                 "figures cover a minority of the log\n",
                 what.c_str(), e.missing, e.used + e.missing);
  return true;
}

// The checks of the reference (relation_audit.h), within the window, for our estimate.
bool PrintAudit(const std::string& name, const std::string& win, const eval::carmen::CarmenLog& log,
                const std::vector<eval::carmen::Relation>& relations,
                const std::vector<eval::carmen::TimedPose>& odometry,
                const std::vector<eval::carmen::TimedPose>& estimate, double window_s) {
  constexpr double kStep_m = 0.05, kTolerance_m = 0.002;
  const eval::carmen::LatticeCheck lattice =
      eval::carmen::CheckLattice(relations, odometry, kStep_m, kTolerance_m, window_s);
  const eval::carmen::FitComparison fit = eval::carmen::CompareScanFit(
      relations, log, estimate, eval::carmen::ScanFitOptions{}, window_s);
  if (lattice.relations == 0 || fit.relations == 0) {
    std::fprintf(stderr, "fleetmap-carmen-eval: --audit: no relation within %.0f s to check\n",
                 window_s);
    return false;
  }
  const int differing = lattice.relations - lattice.equal_to_odometry;
  const auto share = [](int n, int of) {
    return of > 0 ? static_cast<double>(n) / of : std::numeric_limits<double>::quiet_NaN();
  };
  const char* n = name.c_str();
  const char* w = win.c_str();
  std::printf("real.%s.%s.ref_equal_odom_share %.3f fraction\n", n, w,
              share(lattice.equal_to_odometry, lattice.relations));
  if (differing > 0)  // else every relation is the odometry's: no step to measure
    std::printf("real.%s.%s.ref_on_5cm_steps_share %.3f fraction\n", n, w,
                share(lattice.on_lattice, differing));
  std::printf("real.%s.%s.scan_fit_ref_m %.4f m\n", n, w, fit.reference_fit_m);
  std::printf("real.%s.%s.scan_fit_ours_m %.4f m\n", n, w, fit.estimate_fit_m);
  std::printf("real.%s.%s.ours_fits_better_share %.3f fraction\n", n, w,
              share(fit.estimate_better, fit.relations));
  std::fprintf(stderr,
               "  audit %-6s %5d relations: %d equal to the odometry, %d of the other %d a whole "
               "number of 5 cm steps from it; scans overlap better placed by ours in %d, by "
               "the reference in %d (mean distance %.4f vs %.4f m)\n",
               w, lattice.relations, lattice.equal_to_odometry, lattice.on_lattice, differing,
               fit.estimate_better, fit.reference_better, fit.estimate_fit_m, fit.reference_fit_m);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  CLI::App app("", "fleetmap-carmen-eval");
  DefineFlags(app, args);
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  if (app.count("--scan-latency") > 0) args.interpolate_odometry = true;
  if (const core::Status s = MapperOptions(args).Validate(); !s.ok())
    return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n", s.ToString().c_str()), 2;
  const std::string name = args.name.empty() ? Stem(args.carmen) : args.name;
  auto log = eval::carmen::ReadCarmenLog(args.carmen);
  if (!log.ok())
    return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n", log.status().ToString().c_str()), 1;
  auto relations = eval::carmen::ReadRelations(args.relations);
  if (!relations.ok())
    return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n",
                        relations.status().ToString().c_str()),
           1;
  const int interpolated = args.interpolate_odometry
                               ? eval::carmen::InterpolateOdometryAtScans(*log, args.scan_latency_s)
                               : 0;
  std::fprintf(stderr,
               "fleetmap-carmen-eval: %s: %zu scans (%d with odometry interpolated at the scan "
               "time), %zu relations\n",
               args.carmen.c_str(), log->lasers.size(), interpolated, relations->size());
  std::vector<eval::carmen::TimedPose> odometry;
  for (const auto& r : log->lasers) odometry.push_back({r.stamp_s, r.odom_pose});
  const std::string win = "win" + std::to_string(static_cast<int>(args.window_s));
  if (!args.trajectory.empty()) {
    auto external = eval::carmen::ReadTrajectory(args.trajectory);
    if (!external.ok())
      return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n",
                          external.status().ToString().c_str()),
             1;
    std::fprintf(stderr, "  %s: %zu poses\n", args.trajectory.c_str(), external->size());
    if (!Score(name, "all", *relations, *external) ||
        !Score(name, win, *relations, *external, args.window_s))
      return 1;
    if (args.audit && !PrintAudit(name, win, *log, *relations, odometry, *external, args.window_s))
      return 1;
    if (args.png.empty()) return 0;
    if (external->size() != log->lasers.size())
      return std::fprintf(stderr, "fleetmap-carmen-eval: --png needs one pose per scan\n"), 1;
    const core::Status s = DrawMap(*log, *external, args.png);
    if (!s.ok()) return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n", s.ToString().c_str()), 1;
    return 0;
  }
  // The matcher gives a pose at every scan's stamp, as the odometry does: relations that the
  // odometry cannot be scored by, the matcher cannot either; said before minutes of matching.
  for (const double span_s : {std::numeric_limits<double>::infinity(), args.window_s}) {
    const core::Status s = eval::carmen::CheckScored(
        eval::carmen::ScoreRelations(*relations, odometry, span_s), *relations, odometry, span_s);
    if (!s.ok()) return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n", s.ToString().c_str()), 1;
  }
  double ms_per_scan = 0;
  const auto matched = RunMatcher(*log, args, ms_per_scan);
  if (!Score(name, "all", *relations, matched) ||
      !Score(name, win, *relations, matched, args.window_s) ||
      !Score(name, "odom.all", *relations, odometry) ||
      !Score(name, "odom." + win, *relations, odometry, args.window_s))
    return 1;
  if (args.audit && !PrintAudit(name, win, *log, *relations, odometry, matched, args.window_s))
    return 1;
  if (!args.save_trajectory.empty()) {
    const core::Status s = eval::carmen::WriteTrajectory(args.save_trajectory, matched);
    if (!s.ok()) return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n", s.ToString().c_str()), 1;
  }
  std::printf("real.%s.ms_per_scan %.4f ms\n", name.c_str(), ms_per_scan);
  if (!args.png.empty()) {
    const core::Status s = DrawMap(*log, matched, args.png);
    if (!s.ok()) return std::fprintf(stderr, "fleetmap-carmen-eval: %s\n", s.ToString().c_str()), 1;
    std::fprintf(stderr, "  map: %s\n", args.png.c_str());
  }
  return 0;
}
