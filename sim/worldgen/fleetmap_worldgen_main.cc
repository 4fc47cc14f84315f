// fleetmap-worldgen: a static map of a generated building (map_server YAML + PGM and a PNG).
// See --help and docs/worldgen.md.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/command_line.h"
#include "core/image/map_render.h"
#include "core/map/map_io.h"
#include "sim/scenario.h"
#include "sim/worldgen/scenario_writer.h"
#include "sim/worldgen/world_generator.h"

namespace {

using namespace fleetmap;

namespace fs = std::filesystem;

// OUT.yaml -> OUT<suffix>
std::string Beside(const std::string& yaml_path, const std::string& suffix) {
  fs::path p(yaml_path);
  return (p.parent_path() / p.stem()).string() + suffix;
}

// Writes a scenario for the map at `map_yaml` (already on disk) to `path`.
int WriteScenario(const core::OccupancyGrid& map, const std::string& map_yaml,
                  const std::string& path, const std::string& name,
                  const sim::worldgen::ScenarioOptions& options) {
  std::error_code ec;
  auto written = sim::worldgen::WriteScenarioFor(map, fs::absolute(map_yaml, ec).string(), options);
  if (written.ok()) written->scenario.name = name;
  const core::Status saved =
      written.ok() ? sim::SaveScenario(written->scenario, path) : written.status();
  if (!saved.ok()) {
    std::fprintf(stderr, "fleetmap-worldgen: %s: %s\n", map_yaml.c_str(), saved.ToString().c_str());
    return 1;
  }
  const sim::Scenario& scenario = written->scenario;
  std::printf(
      "worldgen: scenario %s: %zu vehicles, %zu objects, %zu people and forklifts, %.0f s -> %s\n",
      scenario.name.c_str(), scenario.vehicles.size(), scenario.objects.size(),
      scenario.actors.size(), scenario.duration_s, path.c_str());
  if (!written->fitted.empty())
    std::printf("worldgen: the floor is small for the asked fleet: %s\n", written->fitted.c_str());
  return 0;
}

int Run(int argc, char** argv) {
  CLI::App app(
      "Writes the static map of a generated building: map_server YAML + PGM, and a PNG\n"
      "beside them. The same options and seed give the same map, cell for cell.\n"
      "Exit status: 0 on success, 1 when the map cannot be made or written, 2 on usage errors.",
      "fleetmap-worldgen");
  core::AddVersionFlag(app);
  std::string style_name = "racked_warehouse", out, scenario_for;
  sim::worldgen::WorldOptions o;
  sim::worldgen::ScenarioOptions so;
  double rotation_deg = 0.0;
  bool list = false, no_png = false;
  app.add_flag("--list-styles", list, "print the building styles and their default sizes");
  app.add_option("--style", style_name, "building style (see --list-styles)")
      ->capture_default_str();
  app.add_option("--seed", o.seed, "random seed")->capture_default_str();
  app.add_option("--resolution", o.render.resolution_m, "metres per cell")->capture_default_str();
  app.add_option("--length", o.length_m, "building length in metres (0: the style's choice)")
      ->capture_default_str();
  app.add_option("--width", o.width_m, "building width in metres (0: the style's choice)")
      ->capture_default_str();
  app.add_option("--rotation-deg", rotation_deg, "the building's turn in the grid, degrees")
      ->capture_default_str();
  app.add_flag("--no-png", no_png, "write no PNG picture");
  app.add_option("--scenario-for", scenario_for,
                 "write only a scenario (to OUT.yaml) for this map_server map, e.g. your own");
  CLI::Option* scenario_seed =
      app.add_option("--scenario-seed", so.seed, "the scenario's random seed (default: --seed)");
  app.add_option("--duration", so.duration_s, "the scenario's length, seconds")
      ->capture_default_str();
  app.add_option("--vehicles", so.vehicles, "vehicles, 1 to 5")->capture_default_str();
  app.add_option("--objects-added", so.objects_added, "pallets appearing during the run")
      ->capture_default_str();
  app.add_option("--objects-removed", so.objects_removed, "pallets taken away during the run")
      ->capture_default_str();
  app.add_option("--people", so.people, "people crossing the routes")->capture_default_str();
  app.add_option("--forklifts", so.forklifts, "forklifts driving along routes")
      ->capture_default_str();
  bool exact_fleet = false;
  app.add_flag("--exact-fleet", exact_fleet,
               "refuse a floor too small for the asked fleet (default: fewer vehicles, then no "
               "forklift)");
  app.add_option("OUT.yaml", out,
                 "the map to write (image OUT.pgm, picture OUT.png, scenario "
                 "OUT_scenario.yaml); with --scenario-for, the scenario");
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  so.fit_to_floor = !exact_fleet;
  if (list) {
    for (sim::worldgen::BuildingStyle s : sim::worldgen::AllBuildingStyles()) {
      const sim::worldgen::SizeRange r = sim::worldgen::DefaultSize(s);
      std::printf("%-20s %g-%g m x %g-%g m\n", sim::worldgen::BuildingStyleName(s), r.min_length_m,
                  r.max_length_m, r.min_width_m, r.max_width_m);
    }
    return 0;
  }
  if (out.empty()) {
    std::fprintf(stderr, "fleetmap-worldgen: OUT.yaml is required (see --help)\n");
    return 2;
  }
  std::error_code ec;  // the folder is made when missing; a failure shows when saving
  if (!fs::path(out).parent_path().empty()) fs::create_directories(fs::path(out).parent_path(), ec);
  if (!scenario_for.empty()) {
    auto map = core::LoadMapServerMap(scenario_for);
    if (!map.ok()) {
      std::fprintf(stderr, "fleetmap-worldgen: %s\n", map.status().ToString().c_str());
      return 1;
    }
    return WriteScenario(map->grid, scenario_for, out, fs::path(out).stem().string(), so);
  }
  auto style = sim::worldgen::ParseBuildingStyle(style_name);
  if (!style.ok()) {
    std::fprintf(stderr, "fleetmap-worldgen: --style: %s\n", style.status().message().c_str());
    return 2;
  }
  o.style = *style;
  o.render.rotation_rad = rotation_deg * M_PI / 180.0;
  auto world = sim::worldgen::GenerateWorld(o);
  core::Status saved = world.ok() ? core::SaveMapServerMap(world->map.grid, out) : world.status();
  if (saved.ok() && !no_png) saved = core::RenderGridToPng(world->map.grid, Beside(out, ".png"));
  if (!saved.ok()) {
    std::fprintf(stderr, "fleetmap-worldgen: %s\n", saved.ToString().c_str());
    return 1;
  }
  const core::OccupancyGrid& g = world->map.grid;
  const double n = static_cast<double>(g.geometry().num_cells());
  std::printf(
      "worldgen: %s seed %llu: %.1f m x %.1f m turned %.1f deg, %.3f m/cell, %d x %d cells "
      "(free %.0f%%, occupied %.0f%%, unknown %.0f%%), %zu walls, %zu solids -> %s\n",
      style_name.c_str(), static_cast<unsigned long long>(o.seed), world->plan.length_m,
      world->plan.width_m, rotation_deg, g.geometry().resolution_m(), g.geometry().width(),
      g.geometry().height(), 100.0 * g.CountState(core::CellState::kFree) / n,
      100.0 * g.CountState(core::CellState::kOccupied) / n,
      100.0 * g.CountState(core::CellState::kUnknown) / n, world->plan.walls.size(),
      world->plan.solids.size(), out.c_str());
  if (scenario_seed->count() == 0) so.seed = static_cast<uint32_t>(o.seed);
  return WriteScenario(world->map.grid, out, Beside(out, "_scenario.yaml"),
                       fs::path(out).stem().string(), so);
}

}  // namespace

int main(int argc, char** argv) { return Run(argc, argv); }
