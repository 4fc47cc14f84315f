// fleetmap-suite: the method judged across buildings. See --help and docs/world_suite.md.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "core/command_line.h"
#include "core/io/file_io.h"
#include "eval/suite/job_pool.h"
#include "eval/suite/suite_figures.h"
#include "eval/suite/suite_plan.h"
#include "eval/suite/suite_report.h"
#include "eval/suite/world_preparation.h"

namespace {

using namespace fleetmap;
using namespace fleetmap::eval::suite;
namespace fs = std::filesystem;

struct Options {
  std::string out = "out/suite";
  std::string data_dir;
  std::string livinglab;
  std::string bin_dir;
  std::string aggregator_config;  // passed to every evaluation
  bool quick = false;
  int jobs = 0;
  double duration_s = 0;
  std::vector<std::string> pipelines = {"agents", "truthmaps"};
  std::vector<std::string> only;
  std::vector<std::string> require;
};

std::string ThisProgramsFolder() {
  std::error_code ec;
  return fs::read_symlink("/proc/self/exe", ec).parent_path().string();
}

// The last non-empty line of a file (an evaluation's error message).
std::string LastLine(const std::string& path) {
  auto text = core::ReadFileBytes(path, 1 << 20);
  if (!text.ok()) return "";
  std::string s = *text;
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  const size_t nl = s.rfind('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

bool Selected(const Options& o, const SuiteWorld& w) {
  return o.only.empty() || std::find(o.only.begin(), o.only.end(), w.name) != o.only.end();
}

std::vector<WorldOutcome> Prepare(const Options& o, const SuitePlan& plan) {
  sim::worldgen::ScenarioOptions scenario;
  scenario.duration_s = o.duration_s;
  std::vector<WorldOutcome> outcomes;
  for (const SuiteWorld& w : plan.worlds) {
    if (!Selected(o, w)) continue;
    WorldOutcome outcome;
    outcome.world = w;
    scenario.seed = static_cast<uint32_t>(7 + outcomes.size());
    auto prepared = PrepareWorld(w, (fs::path(o.out) / w.name).string(), scenario);
    if (prepared.ok()) {
      outcome.prepared = *prepared;
      std::fprintf(stderr, "suite: %-32s ready (%.3f m, %.0f x %.0f m)%s%s\n", w.name.c_str(),
                   prepared->resolution_m, prepared->width_m, prepared->height_m,
                   prepared->fitted.empty() ? "" : ": ", prepared->fitted.c_str());
    } else {
      outcome.unusable = prepared.status().ToString();
      std::fprintf(stderr, "suite: %-32s UNUSABLE: %s\n", w.name.c_str(), outcome.unusable.c_str());
    }
    outcomes.push_back(outcome);
  }
  return outcomes;
}

struct PlannedRun {
  size_t world;
  std::string pipeline;
  std::string folder;
};

void Evaluate(const Options& o, std::vector<WorldOutcome>& outcomes) {
  std::vector<Job> jobs;
  std::vector<PlannedRun> runs;
  for (const std::string& pipeline : o.pipelines)
    for (size_t i = 0; i < outcomes.size(); ++i) {
      const WorldOutcome& w = outcomes[i];
      if (!w.unusable.empty()) continue;
      if (w.world.source == WorldSource::kLivingLab && pipeline != "agents") continue;
      const std::string folder = (fs::path(o.out) / w.world.name / pipeline).string();
      std::error_code ec;
      fs::create_directories(folder, ec);
      std::vector<std::string> argv = {(fs::path(o.bin_dir) / "fleetmap-eval").string(),
                                       "--scenario",
                                       w.prepared.scenario_yaml,
                                       "--pipeline",
                                       pipeline,
                                       "--quiet",
                                       "--name",
                                       w.world.name,
                                       "--out",
                                       folder};
      if (!o.aggregator_config.empty())
        argv.insert(argv.end(), {"--aggregator-config", o.aggregator_config});
      jobs.push_back({argv, folder + "/figures.txt", folder + "/eval.log"});
      runs.push_back({i, pipeline, folder});
    }
  const auto start = std::chrono::steady_clock::now();
  size_t finished = 0;
  RunJobs(jobs, o.jobs, [&](size_t j, const JobResult& r) {
    WorldOutcome& w = outcomes[runs[j].world];
    const bool agents = runs[j].pipeline == "agents";
    std::string error;
    if (!r.error.empty()) {
      error = r.error;
    } else if (r.exit_code != 0) {
      error = "fleetmap-eval exit " + std::to_string(r.exit_code) + ": " +
              LastLine(jobs[j].stderr_path);
    } else {
      auto score = ReadWorldScore(runs[j].folder + "/report.json");
      if (score.ok()) {
        score->run_s = r.seconds;
        (agents ? w.agents : w.truthmaps) = *score;
      } else {
        error = score.status().ToString();
      }
    }
    (agents ? w.agents_error : w.truthmaps_error) = error;
    ++finished;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double left = elapsed / finished * (jobs.size() - finished);
    const auto& s = agents ? w.agents : w.truthmaps;
    std::fprintf(stderr,
                 "suite: [%zu/%zu] %-32s %-9s %s (%.0f s)   %.0f min done, ~%.0f min left\n",
                 finished, jobs.size(), w.world.name.c_str(), runs[j].pipeline.c_str(),
                 s ? ("F1 " + std::to_string(s->changed_f1).substr(0, 5)).c_str()
                   : ("FAILED: " + error).c_str(),
                 r.seconds, elapsed / 60, left / 60);
  });
}

// "NAME>=VALUE" or "NAME<=VALUE"; a requirement on a figure that is absent fails.
bool Holds(const std::string& requirement, const std::vector<Figure>& figures, std::string& why) {
  const size_t at = requirement.find_first_of("<>");
  if (at == std::string::npos || at + 1 >= requirement.size() || requirement[at + 1] != '=') {
    why = "not NAME>=VALUE or NAME<=VALUE";
    return false;
  }
  const std::string name = requirement.substr(0, at);
  const core::Result<double> bound_or = core::ParseNumber(requirement.substr(at + 2), name);
  if (!bound_or.ok()) {
    why = "the bound is not a number";
    return false;
  }
  const double bound = *bound_or;
  for (const Figure& f : figures)
    if (f.name == name) {
      const bool ok = requirement[at] == '>' ? f.value >= bound : f.value <= bound;
      why = name + " is " + std::to_string(f.value);
      return ok;
    }
  why = name + " was not measured";
  return false;
}

core::Status WriteOutputs(const Options& o, const std::vector<WorldOutcome>& outcomes,
                          const std::vector<Figure>& figures) {
  nlohmann::json json;
  for (const Figure& f : figures) json["figures"][f.name] = {{"value", f.value}, {"unit", f.unit}};
  for (const WorldOutcome& w : outcomes) {
    nlohmann::json& j = json["worlds"][w.world.name];
    j["group"] = w.world.group;
    if (!w.unusable.empty()) j["unusable"] = w.unusable;
    if (!w.prepared.fitted.empty()) j["fitted"] = w.prepared.fitted;
    if (!w.agents_error.empty()) j["agents_error"] = w.agents_error;
    if (!w.truthmaps_error.empty()) j["truthmaps_error"] = w.truthmaps_error;
  }
  const fs::path out(o.out);
  FLEETMAP_RETURN_IF_ERROR(
      core::WriteFileAtomically((out / "suite.json").string(), json.dump(2) + "\n"));
  FLEETMAP_RETURN_IF_ERROR(
      core::WriteFileAtomically((out / "suite.md").string(), SuiteMarkdown(outcomes, figures)));
  return WriteSuitePng(outcomes, (out / "suite.png").string());
}

int Run(int argc, char** argv) {
  CLI::App app(
      "Runs the world suite: generated buildings of every style, turn and resolution, every\n"
      "public map of DATA_DIR/worlds and the LivingLab hall, each through fleetmap-eval with\n"
      "the pipelines agents and truthmaps; prints every figure as `name value unit` lines\n"
      "and writes OUT/suite.md (a table per world), OUT/suite.png (F1 per world) and\n"
      "OUT/suite.json. A world that cannot be used is reported by name and reason and left\n"
      "out of the aggregate.\n"
      "Exit status: 0 on success, 1 when no world could be scored or an output cannot be\n"
      "written, 2 on usage errors, 3 when a --require does not hold.",
      "fleetmap-suite");
  core::AddVersionFlag(app);
  Options o;
  const char* data = std::getenv("FLEETMAP_DATA_DIR");
  o.data_dir = data && *data ? data : "../shared/data";
  o.bin_dir = ThisProgramsFolder();
  o.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  app.add_option("--out", o.out, "output folder")->capture_default_str();
  app.add_option("--data-dir", o.data_dir,
                 "data folder; public maps in its worlds/ (default: "
                 "FLEETMAP_DATA_DIR, else ../shared/data)");
  app.add_option("--livinglab", o.livinglab,
                 "the LivingLab scenario, reported as suite.livinglab.changed_f1 (e.g. "
                 "sim/worlds/livinglab/fleet.yaml); none: left out");
  app.add_flag("--quick", o.quick, "about 8 small worlds, shorter runs (the test suite's check)");
  app.add_option("--jobs", o.jobs, "evaluations at once")->capture_default_str();
  app.add_option("--duration", o.duration_s,
                 "scenario length in seconds (default 180, with --quick 150)");
  app.add_option("--pipelines", o.pipelines, "pipelines to run")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--only", o.only, "run only these worlds (by name; repeat)");
  app.add_option("--require", o.require,
                 "a figure that must hold, e.g. 'suite.changed_f1.min>=0.9' (repeat)");
  app.add_option("--aggregator-config", o.aggregator_config,
                 "a fleetmap-aggregator configuration whose aggregator: options every "
                 "evaluation uses (default: the built-in defaults)")
      ->check(CLI::ExistingFile);
  app.add_option("--bin-dir", o.bin_dir, "the folder of fleetmap-eval")->capture_default_str();
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  for (const std::string& p : o.pipelines)
    if (p != "agents" && p != "truthmaps") {
      std::fprintf(stderr, "fleetmap-suite: --pipelines: '%s' is not agents or truthmaps\n",
                   p.c_str());
      return 2;
    }
  if (!(o.duration_s >= 0)) {
    std::fprintf(stderr, "fleetmap-suite: --duration must be positive\n");
    return 2;
  }
  if (o.duration_s == 0) o.duration_s = o.quick ? 150.0 : 180.0;
  if (!o.aggregator_config.empty()) o.aggregator_config = fs::absolute(o.aggregator_config);

  const SuitePlan plan =
      PlanSuite({o.quick, (fs::path(o.data_dir) / "worlds").string(), o.livinglab});
  for (const std::string& note : plan.notes) std::fprintf(stderr, "suite: %s\n", note.c_str());
  std::vector<WorldOutcome> outcomes = Prepare(o, plan);
  Evaluate(o, outcomes);
  auto figures = SuiteFigures(outcomes);
  if (!figures.ok()) {
    std::fprintf(stderr, "fleetmap-suite: %s\n", figures.status().ToString().c_str());
    return 1;
  }
  std::fputs(FigureLines(*figures).c_str(), stdout);
  const core::Status written = WriteOutputs(o, outcomes, *figures);
  if (!written.ok()) {
    std::fprintf(stderr, "fleetmap-suite: %s\n", written.ToString().c_str());
    return 1;
  }
  std::fprintf(stderr, "suite: wrote %s/suite.md, suite.png, suite.json\n", o.out.c_str());
  int failed = 0;
  for (const std::string& r : o.require) {
    std::string why;
    const bool ok = Holds(r, *figures, why);
    failed += !ok;
    std::fprintf(stderr, "suite: require %s: %s (%s)\n", r.c_str(), ok ? "holds" : "FAILS",
                 why.c_str());
  }
  return failed ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) { return Run(argc, argv); }
