#include "eval/suite/world_preparation.h"

#include <filesystem>

#include "core/image/map_render.h"
#include "core/map/map_io.h"
#include "sim/scenario.h"

namespace fleetmap::eval::suite {
namespace {

namespace fs = std::filesystem;

// A scenario needs a few metres of free floor at least: a 2 x 2 m room.
constexpr double kMinFreeAreaM2 = 4.0;

PreparedWorld Describe(const core::OccupancyGrid& map) {
  PreparedWorld p;
  const core::GridGeometry& g = map.geometry();
  p.resolution_m = g.resolution_m();
  p.width_m = g.width() * g.resolution_m();
  p.height_m = g.height() * g.resolution_m();
  return p;
}

core::Result<core::OccupancyGrid> MapOf(const SuiteWorld& world, const std::string& folder) {
  if (world.source == WorldSource::kGenerated) {
    auto generated = sim::worldgen::GenerateWorld(world.generated);
    if (!generated.ok()) return generated.status().WithContext("generating");
    const std::string yaml = (fs::path(folder) / "map.yaml").string();
    FLEETMAP_RETURN_IF_ERROR(core::SaveMapServerMap(generated->map.grid, yaml));
    FLEETMAP_RETURN_IF_ERROR(
        core::RenderGridToPng(generated->map.grid, (fs::path(folder) / "map.png").string()));
    return std::move(generated->map.grid);
  }
  if (world.map_yaml.empty())
    return core::NotFound("no single map_server YAML in the map's folder");
  auto loaded = core::LoadMapServerMap(world.map_yaml);
  if (!loaded.ok()) return loaded.status();
  return std::move(loaded->grid);
}

}  // namespace

core::Status CheckMapUsable(const core::OccupancyGrid& map) {
  const core::GridGeometry& g = map.geometry();
  if (g.num_cells() == 0) return core::FailedPrecondition("the map has no cells");
  if (!(g.resolution_m() > 0))
    return core::FailedPrecondition("the map's resolution is not positive");
  const int64_t free = map.CountState(core::CellState::kFree);
  const int64_t occupied = map.CountState(core::CellState::kOccupied);
  if (free == 0 && occupied == 0)
    return core::FailedPrecondition("nothing in the map is observed: every cell is unknown");
  const double free_m2 = static_cast<double>(free) * g.resolution_m() * g.resolution_m();
  if (free_m2 < kMinFreeAreaM2)
    return core::FailedPrecondition("the map has " + std::to_string(free_m2) +
                                    " m2 of free floor, too little for a route");
  if (occupied == 0)
    return core::FailedPrecondition("the map has no occupied cell: nothing to localize on");
  return core::OkStatus();
}

core::Result<PreparedWorld> PrepareWorld(const SuiteWorld& world, const std::string& folder,
                                         const sim::worldgen::ScenarioOptions& scenario) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) return core::IoError("cannot make " + folder + ": " + ec.message());
  if (world.source == WorldSource::kLivingLab) {
    auto shipped = sim::LoadScenario(world.scenario_yaml);
    if (!shipped.ok()) return shipped.status();
    auto map = core::LoadMapServerMap(shipped->map_yaml);
    if (!map.ok()) return map.status();
    PreparedWorld p = Describe(map->grid);
    p.scenario_yaml = world.scenario_yaml;
    return p;
  }
  auto map = MapOf(world, folder);
  if (!map.ok()) return map.status();
  FLEETMAP_RETURN_IF_ERROR(CheckMapUsable(*map));
  const std::string map_yaml = world.source == WorldSource::kGenerated
                                   ? fs::absolute(fs::path(folder) / "map.yaml", ec).string()
                                   : fs::absolute(world.map_yaml, ec).string();
  auto written = sim::worldgen::WriteScenarioFor(*map, map_yaml, scenario);
  if (!written.ok()) return written.status().WithContext("scenario");
  written->scenario.name = world.name;
  PreparedWorld p = Describe(*map);
  p.fitted = written->fitted;
  p.scenario_yaml = (fs::path(folder) / "scenario.yaml").string();
  FLEETMAP_RETURN_IF_ERROR(sim::SaveScenario(written->scenario, p.scenario_yaml));
  return p;
}

}  // namespace fleetmap::eval::suite
