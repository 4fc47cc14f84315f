// fleetmap-eval: runs a scenario through a pipeline in-process and scores it against the
// simulator's ground truth. See --help.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/file_io.h"
#include "core/map_io.h"
#include "core/map_render.h"
#include "tools/eval/eval_figures.h"
#include "tools/eval/pipeline.h"

namespace {

using namespace fleetmap;

constexpr const char* kUsage = R"(usage: fleetmap-eval --scenario SCENARIO.yaml [options]

Runs the scenario through a pipeline, in-process and faster than real time, scores the run
against the simulator's ground truth and writes, into the output folder:
  report.json (stable keys, docs/evaluation.md), report.md, current_map.{yaml,pgm,png},
  map_overlay.png (the map against the truth), divergence.png (d(t), w_avg, w_fast, w_slow),
  paths.png (the vehicles' paths)
and prints the figures as `eval.<name>.<figure> value unit` lines.

options:
  --scenario FILE   scenario YAML (required)
  --map FILE        static map (map_server YAML) instead of the one the scenario names
  --pipeline NAME   oracle (merges exactly what the scanners saw; the reference)  [oracle]
  --out DIR         output folder                                 [out/eval/<scenario name>]
  --name NAME       name used in the figure lines                 [the scenario's name]
  --quiet           no progress lines on stderr
  -h, --help        this text
Exit status: 0 on success, 1 when the scenario, the map or an output cannot be used, 2 on
usage errors.
)";

struct Args {
  std::string scenario, map, pipeline = "oracle", out, name;
  bool quiet = false;
};

bool Parse(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string& dst) {
      if (i + 1 >= argc) return false;
      dst = argv[++i];
      return true;
    };
    if (arg == "--scenario"   ? !value(a.scenario)
        : arg == "--map"      ? !value(a.map)
        : arg == "--pipeline" ? !value(a.pipeline)
        : arg == "--out"      ? !value(a.out)
        : arg == "--name"     ? !value(a.name)
        : arg == "--quiet"    ? (a.quiet = true, false)
                              : true) {
      std::fprintf(stderr, "fleetmap-eval: bad or incomplete argument '%s'\n", arg.c_str());
      return false;
    }
  }
  return !a.scenario.empty();
}

void Progress(double t_s) { std::fprintf(stderr, "  simulated %.0f s\n", t_s); }

int Fail(const core::Status& s) {
  std::fprintf(stderr, "fleetmap-eval: %s\n", s.ToString().c_str());
  return 1;
}

void Figure(const std::string& name, const char* figure, double value, const char* unit) {
  std::printf("eval.%s.%s %.6g %s\n", name.c_str(), figure, value, unit);
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
  }
  Args args;
  if (!Parse(argc, argv, args)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  if (args.pipeline != "oracle") {
    std::fprintf(stderr, "fleetmap-eval: unknown pipeline '%s' (known: oracle)\n",
                 args.pipeline.c_str());
    return 2;
  }
  auto world = sim::World::Load(args.scenario, args.map);
  if (!world.ok()) return Fail(world.status());
  const std::string name = args.name.empty() ? world->scenario().name : args.name;
  const std::string out = args.out.empty() ? "out/eval/" + name : args.out;
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return Fail(core::IoError(out + ": " + ec.message()));

  if (!args.quiet) {
    std::fprintf(stderr, "fleetmap-eval: %s (%zu vehicles, %.0f s) through the %s pipeline\n",
                 args.scenario.c_str(), world->scenario().vehicles.size(),
                 world->scenario().duration_s, args.pipeline.c_str());
  }
  sim::Simulator simulator(&*world);
  auto pipeline = eval::MakeOraclePipeline();
  const eval::RunRecord run =
      eval::RunScenario(*world, *pipeline, simulator, args.quiet ? nullptr : Progress);
  const eval::EvalReport report = eval::Evaluate(*world, simulator.observations(), run);

  for (const core::Status& s :
       {core::WriteFileAtomically(out + "/report.json", eval::ReportJson(report)),
        core::WriteFileAtomically(out + "/report.md", eval::ReportMarkdown(report)),
        core::SaveMapServerMap(run.final_map, out + "/current_map.yaml"),
        core::RenderGridToPng(run.final_map, out + "/current_map.png"),
        eval::WriteOverlayPng(*world, simulator.observations(), run, out + "/map_overlay.png"),
        eval::WriteDivergencePng(run, out + "/divergence.png"),
        eval::WritePathsPng(*world, run, out + "/paths.png")}) {
    if (!s.ok()) return Fail(s);
  }
  const eval::ChangeScores& c = report.changes;
  Figure(name, "changed_f1", c.f1, "ratio");
  Figure(name, "static_erased", double(c.static_cells_erased), "cells");
  Figure(name, "actor_mapped", double(c.actor_cells_mapped), "cells");
  Figure(name, "align_trans_median_cells", report.align_translation_cells.median, "cells");
  Figure(name, "align_trans_p95_cells", report.align_translation_cells.p95, "cells");
  Figure(name, "align_rot_p95_deg", report.align_rotation_deg.p95, "deg");
  Figure(name, "detect_latency_median_s", report.detection_latency_s.median, "s");
  if (!args.quiet)
    std::fprintf(stderr, "fleetmap-eval: wrote %s/report.json and figures\n", out.c_str());
  return 0;
}
