// fleetmap-eval: runs a scenario through a pipeline in-process and scores it against the
// simulator's ground truth. See --help.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "aggregator/node/node_config.h"
#include "auth/key.h"
#include "core/command_line.h"
#include "core/image/map_render.h"
#include "core/io/file_io.h"
#include "core/map/map_io.h"
#include "eval/agents_pipeline.h"
#include "eval/eval_figures.h"
#include "eval/pipeline.h"
#include "eval/recording/recorded_run.h"
#include "eval/truth_tempmap_pipeline.h"

namespace {

using namespace fleetmap;

constexpr char kDescription[] =
    R"(Runs the scenario through a pipeline, in-process and faster than real time, scores the run
against the simulator's ground truth and writes, into the output folder:
  report.json (stable keys, docs/evaluation.md), report.md, current_map.{yaml,pgm,png},
  map_overlay.png (the map against the truth), divergence.png (d(t), w_avg, w_fast, w_slow),
  paths.png (the vehicles' paths)
and prints the figures as `eval.<name>.<figure> value unit` lines.
Pipelines: oracle merges exactly what the scanners saw (the reference); agents is the real
system in-process (each vehicle's on-board pipeline: localization, divergence, temporary
maps; and the aggregator); truthmaps: temporary maps a perfect vehicle builds at its true
poses, anchored with a random error, aligned and merged by the aggregator.)";

constexpr char kFooter[] =
    R"(Exit status: 0 on success, 1 when the scenario, the map or an output cannot be used, 2 on
usage errors.)";

struct Args {
  std::string scenario, map, pipeline = "oracle", out, name, align_mode, aggregator_config;
  double anchor_error_m = 0.3, anchor_error_deg = 3;
  int confirmations = 0;  // 0: the aggregator's setting
  uint32_t seed = 0;
  bool quiet = false;
  std::vector<std::string> lcm_logs, vehicle_maps;
  double epoch_s = 0, duration_s = 0;  // duration 0: the scenario's
  std::string key_file, aggregator_name = "aggregator";
};

void DefineFlags(CLI::App& app, Args& a) {
  app.description(kDescription);
  app.footer(kFooter);
  core::AddVersionFlag(app);
  app.add_option("--scenario", a.scenario, "scenario YAML")->required()->type_name("FILE");
  app.add_option("--map", a.map,
                 "static map (map_server YAML) instead of the one the scenario names")
      ->type_name("FILE");
  app.add_option("--pipeline", a.pipeline, "oracle, agents or truthmaps")
      ->check(CLI::IsMember({"oracle", "truthmaps", "agents"}))
      ->capture_default_str();
  app.add_option("--aggregator-config", a.aggregator_config,
                 "agents, truthmaps: the aggregator's options from a fleetmap-aggregator "
                 "configuration (its aggregator: section; the flags below override it where "
                 "given) [the defaults of docs/aggregator.md]")
      ->type_name("FILE");
  app.add_option("--align-mode", a.align_mode,
                 "alignment: ours (dominant directions) or paper (the paper's sequence) [ours]")
      ->type_name("MODE");
  app.add_option("--anchor-error-m", a.anchor_error_m,
                 "truthmaps: largest anchor translation error, metres")
      ->check(core::Finite() & CLI::Range(0.0, 1e3))
      ->capture_default_str();
  app.add_option("--anchor-error-deg", a.anchor_error_deg,
                 "truthmaps: largest anchor rotation error, degrees")
      ->check(core::Finite() & CLI::Range(0.0, 180.0))
      ->capture_default_str();
  app.add_option("--confirmations", a.confirmations,
                 "temporary maps of different times that must see an obstacle before it is "
                 "added: 1 (the paper) or 2 [2]")
      ->check(CLI::IsMember({1, 2}));
  app.add_option("--seed", a.seed, "truthmaps: added to the scenario's seed for the anchor errors")
      ->check(core::WholeNumber())
      ->capture_default_str();
  app.add_option("--lcm-log", a.lcm_logs,
                 "score a recorded fleet run instead of running a pipeline: the lcm-logger "
                 "logs of its sensor, uplink and downlink groups (repeat the flag); adds fleet.* "
                 "keys (bytes per channel per simulated second, change latency in wall-clock "
                 "seconds) to report.json")
      ->type_name("FILE")
      ->allow_extra_args(false);  // one file per flag; the flag repeats
  app.add_option("--epoch", a.epoch_s,
                 "recorded run: the epoch fleetmap-sim added to simulated time")
      ->check(core::Finite())
      ->capture_default_str();
  app.add_option("--duration", a.duration_s,
                 "recorded run: the simulated seconds it ran [the scenario's duration]")
      ->check(core::Positive());
  app.add_option("--vehicle-map", a.vehicle_maps,
                 "recorded run: a vehicle's final map (fleetmap-agent --final-map), compared "
                 "cell by cell with the fleet's final map (repeat the flag)")
      ->type_name("ID=FILE")
      ->allow_extra_args(false);  // one file per flag; the flag repeats
  app.add_option("--key-file", a.key_file,
                 "recorded run: the fleet's key; a message counts only if its MAC is right "
                 "[none: a message counts if it names its channel's owner]")
      ->type_name("FILE");
  app.add_option("--aggregator-name", a.aggregator_name,
                 "recorded run: the aggregator's process name, the only sender whose word on "
                 "the downlink counts")
      ->capture_default_str();
  app.add_option("--out", a.out, "output folder [out/eval/<scenario name>]")->type_name("DIR");
  app.add_option("--name", a.name, "name used in the figure lines [the scenario's name]");
  app.add_flag("--quiet", a.quiet, "no progress lines on stderr");
}

void Progress(double t_s) { std::fprintf(stderr, "  simulated %.0f s\n", t_s); }

// Every merge with its outcome and residual against the truth (line tables: report.md).
std::string MergeTable(const eval::RunRecord& run, double resolution_m) {
  std::string table =
      "| vehicle | seq | closed (s) | accepted | added | removed | lines | residual x, y (cells), "
      "theta (deg) | anchor's x, y (cells), theta (deg) | builder's drift (m, deg) | "
      "correction's Mahalanobis², fit gain | reason |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const eval::MergeRecord& m : run.merges) {
    const core::Pose2 e = core::Between(m.true_origin, m.placed_origin);
    const core::Pose2 a = core::Between(m.true_origin, m.anchor_origin);
    char row[256];
    std::snprintf(row, sizeof(row),
                  "| %s | %d | %.1f | %s | %d | %d | %zu | %.2f, %.2f, %.3f | %.2f, %.2f, %.3f | ",
                  m.vehicle_id.c_str(), m.tempmap_seq, m.closed_s, m.accepted ? "yes" : "no",
                  m.cells_added, m.cells_removed, m.lines.size(), e.x_m / resolution_m,
                  e.y_m / resolution_m, e.theta_rad * 180 / M_PI, a.x_m / resolution_m,
                  a.y_m / resolution_m, a.theta_rad * 180 / M_PI);
    char drift[64] = "-";  // perfect maps and recorded runs do not know it
    if (std::isfinite(m.drift_m))
      std::snprintf(drift, sizeof(drift), "%.3f, %.3f", m.drift_m, m.drift_deg);
    char gate[64] = "-";  // no covariance travelled, or nothing aligned
    if (std::isfinite(m.correction_mahalanobis_sq) || std::isfinite(m.fit_gain))
      std::snprintf(gate, sizeof(gate), "%.2f, %.3f", m.correction_mahalanobis_sq, m.fit_gain);
    table += row + std::string(drift) + " | " + gate + " | " + m.reason + " |\n";
  }
  return table;
}

int Fail(const core::Status& s) {
  std::fprintf(stderr, "fleetmap-eval: %s\n", s.ToString().c_str());
  return 1;
}

// The aggregator's options: the configuration file's, if one is given, with the flags that
// were given on top.
core::Result<aggregator::AggregatorOptions> AggregatorOptionsFor(const Args& args) {
  aggregator::AggregatorOptions options;
  if (!args.aggregator_config.empty()) {
    auto config = aggregator::node::LoadProcessConfig(args.aggregator_config);
    if (!config.ok()) return config.status();
    options = config->aggregator;
  }
  if (!args.align_mode.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(options.alignment.mode,
                              aggregator::ParseAlignmentMode(args.align_mode));
  }
  if (args.confirmations != 0) options.merge.confirmations = args.confirmations;
  return options;
}

// The pipeline the arguments name, or a usage error (exit 2) / another error (exit 1).
core::Result<std::unique_ptr<eval::Pipeline>> MakePipeline(const Args& args,
                                                           const sim::World& world) {
  if (args.pipeline == "oracle") return eval::MakeOraclePipeline();
  auto aggregator = AggregatorOptionsFor(args);
  if (!aggregator.ok()) return aggregator.status();
  if (args.pipeline == "agents") {
    eval::AgentsPipelineOptions agents;
    agents.aggregator = *aggregator;
    return eval::MakeAgentsPipeline(world, agents);
  }
  eval::TruthTempMapOptions options;
  options.aggregator = *aggregator;
  options.anchor_error_max_m = args.anchor_error_m;
  options.anchor_error_max_rad = args.anchor_error_deg * M_PI / 180.0;
  options.seed = args.seed;
  return eval::MakeTruthTempMapPipeline(world, options);
}

void Figure(const std::string& name, const char* figure, double value, const char* unit) {
  std::printf("eval.%s.%s %.6g %s\n", name.c_str(), figure, value, unit);
}

int WriteResults(const Args& args, const sim::World& world, const sim::Simulator& simulator,
                 const eval::RunRecord& run, const eval::EvalReport& report,
                 const std::string& name, const std::string& out,
                 const std::vector<std::pair<std::string, std::string>>& extra_json) {
  const std::string json = eval::ReportJson(report, extra_json);
  for (const core::Status& s :
       {core::WriteFileAtomically(out + "/report.json", json),
        core::WriteFileAtomically(out + "/report.md", eval::ReportMarkdown(report)),
        core::WriteFileAtomically(out + "/merges.md",
                                  MergeTable(run, world.geometry().resolution_m())),
        core::SaveMapServerMap(run.final_map, out + "/current_map.yaml"),
        core::RenderGridToPng(run.final_map, out + "/current_map.png"),
        eval::WriteOverlayPng(world, simulator.observations(), run, out + "/map_overlay.png"),
        eval::WriteDivergencePng(run, out + "/divergence.png"),
        eval::WritePathsPng(world, run, out + "/paths.png")}) {
    if (!s.ok()) return Fail(s);
  }
  const eval::ChangeScores& c = report.changes;
  if (std::isnan(c.f1)) {  // the files are written (for a look); the figures are not
    return Fail(core::FailedPrecondition(
        "no changed cell to score: the truth holds no added or removed cell and the map "
        "none either (a scenario, or a --duration, in which nothing changed that a scanner "
        "saw); changed-cell F1 is undefined, see " +
        out + "/report.md"));
  }
  Figure(name, "changed_f1", c.f1, "ratio");
  Figure(name, "static_erased", double(c.static_cells_erased), "cells");
  Figure(name, "actor_mapped", double(c.actor_cells_mapped), "cells");
  Figure(name, "align_trans_median_cells", report.align_translation_cells.median, "cells");
  Figure(name, "align_trans_p95_cells", report.align_translation_cells.p95, "cells");
  Figure(name, "anchor_trans_p95_cells", report.anchor_translation_cells.p95, "cells");
  if (report.anchor_nees.count > 0) {  // only where the vehicles sent their covariance
    Figure(name, "anchor_nees_median", report.anchor_nees.median, "ratio");
    Figure(name, "anchor_nees_p95", report.anchor_nees.p95, "ratio");
  }
  Figure(name, "align_rot_p95_deg", report.align_rotation_deg.p95, "deg");
  Figure(name, "detect_latency_median_s", report.detection_latency_s.median, "s");
  Figure(name, "align_trans_max_cells", report.align_translation_cells.max, "cells");
  Figure(name, "align_rot_median_deg", report.align_rotation_deg.median, "deg");
  Figure(name, "align_rot_max_deg", report.align_rotation_deg.max, "deg");
  Figure(name, "merges_accepted", report.merges_accepted, "merges");
  Figure(name, "merges_rejected", report.merges_rejected, "merges");
  if (report.tempmap_drift_m.count > 0) {  // only the agents pipeline knows its builders' drift
    Figure(name, "tempmap_drift_p95_m", report.tempmap_drift_m.p95, "m");
    Figure(name, "tempmap_drift_p95_deg", report.tempmap_drift_deg.p95, "deg");
  }
  if (!args.quiet)
    std::fprintf(stderr, "fleetmap-eval: wrote %s/report.json and figures\n", out.c_str());
  return 0;
}

// How many vehicles' final maps (ID=FILE) hold exactly the fleet's final map, cell state by
// cell state; each one that differs is named on stderr.
core::Result<int> CountVehiclesHoldingMap(const std::vector<std::string>& vehicle_maps,
                                          const core::OccupancyGrid& fleet_map) {
  const core::TriStateClassifier classify;
  int same = 0;
  for (const std::string& spec : vehicle_maps) {
    const size_t eq = spec.find('=');
    if (eq == std::string::npos || eq == 0)
      return core::InvalidArgument("--vehicle-map needs ID=FILE, not '" + spec + "'");
    auto loaded = core::LoadMapServerMap(spec.substr(eq + 1));
    if (!loaded.ok()) return loaded.status();
    const core::OccupancyGrid& map = loaded->grid;
    size_t differ = 0;
    if (map.cells().size() != fleet_map.cells().size()) differ = map.cells().size();
    for (size_t i = 0; differ == 0 && i < map.cells().size(); ++i)
      differ = classify(map.cells()[i]) != classify(fleet_map.cells()[i]) ? i + 1 : 0;
    if (differ == 0) {
      ++same;
    } else {
      std::fprintf(stderr,
                   "fleetmap-eval: vehicle %s does not hold the fleet's final map (other "
                   "size, or cell %zu differs)\n",
                   spec.substr(0, eq).c_str(), differ - 1);
    }
  }
  return same;
}

// Scores a fleet run recorded by lcm-logger: the simulator runs again (it is deterministic)
// for the ground truth; the logs give what the system did.
int RunRecorded(const Args& args, const sim::World& world, const std::string& name,
                const std::string& out) {
  eval::recording::RecordedRunOptions options;
  options.epoch_s = args.epoch_s;
  options.aggregator_sender = args.aggregator_name;
  if (!args.key_file.empty()) {
    auto key = auth::ReadKeyFile(args.key_file);
    if (!key.ok()) return Fail(key.status());
    options.fleet_key = *key;
  }
  const double duration = args.duration_s > 0 ? args.duration_s : world.scenario().duration_s;
  options.duration_s = duration;
  if (!std::isfinite(options.epoch_s) || !(duration > 0)) {
    std::fprintf(stderr, "fleetmap-eval: --epoch and --duration take numbers (duration > 0)\n");
    return 2;
  }
  sim::Simulator simulator(&world);
  while (auto event = simulator.Next())
    if (sim::EventTime(*event) > duration) break;
  auto recorded = eval::recording::ReadRecordedRun(args.lcm_logs, world, options);
  if (!recorded.ok()) return Fail(recorded.status());
  recorded->run.pipeline = "fleet";
  const eval::EvalReport report = eval::Evaluate(world, simulator.observations(), recorded->run);
  auto pairs = eval::recording::FleetJsonPairs(recorded->fleet);
  std::string lines = eval::recording::FleetFigureLines(recorded->fleet);
  if (!args.vehicle_maps.empty()) {
    auto same = CountVehiclesHoldingMap(args.vehicle_maps, recorded->run.final_map);
    if (!same.ok()) return Fail(same.status());
    pairs.emplace_back("fleet.vehicle_maps_equal", std::to_string(*same));
    pairs.emplace_back("fleet.vehicle_maps", std::to_string(args.vehicle_maps.size()));
    lines += "fleet.vehicle_maps_equal " + std::to_string(*same) + " count\n";
  }
  const int rc = WriteResults(args, world, simulator, recorded->run, report, name, out, pairs);
  std::fputs(lines.c_str(), stdout);
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  CLI::App app("", "fleetmap-eval");
  DefineFlags(app, args);
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  auto world = sim::World::Load(args.scenario, args.map);
  if (!world.ok()) return Fail(world.status());
  const std::string name = args.name.empty() ? world->scenario().name : args.name;
  const std::string out = args.out.empty() ? "out/eval/" + name : args.out;
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return Fail(core::IoError(out + ": " + ec.message()));
  if (!args.lcm_logs.empty()) return RunRecorded(args, *world, name, out);

  if (!args.quiet) {
    std::fprintf(stderr, "fleetmap-eval: %s (%zu vehicles, %.0f s) through the %s pipeline\n",
                 args.scenario.c_str(), world->scenario().vehicles.size(),
                 world->scenario().duration_s, args.pipeline.c_str());
  }
  auto pipeline = MakePipeline(args, *world);
  if (!pipeline.ok()) {
    std::fprintf(stderr, "fleetmap-eval: %s\n", pipeline.status().ToString().c_str());
    return pipeline.status().code() == core::StatusCode::kInvalidArgument ? 2 : 1;
  }
  sim::Simulator simulator(&*world);
  const eval::RunRecord run =
      eval::RunScenario(*world, **pipeline, simulator, args.quiet ? nullptr : Progress);
  const eval::EvalReport report = eval::Evaluate(*world, simulator.observations(), run);
  return WriteResults(args, *world, simulator, run, report, name, out, {});
}
