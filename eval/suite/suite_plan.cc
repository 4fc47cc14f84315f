#include "eval/suite/suite_plan.h"

#include <algorithm>
#include <filesystem>
#include <iterator>

namespace fleetmap::eval::suite {
namespace {

namespace fs = std::filesystem;

// One building of every style per variant: together every style at every resolution from
// 0.02 to 0.10 m, turned by many angles, from small rooms to the style's largest halls.
// A size of 0 lets the seed draw it from the style's range (sim::worldgen::DefaultSize).
struct Variant {
  double resolution_m, rotation_deg, length_m, width_m;
};
constexpr Variant kVariants[] = {
    {0.05, 0.0, 0, 0},  {0.02, 15.0, 26, 18}, {0.03, 30.0, 40, 26}, {0.10, 45.0, 0, 0},
    {0.075, 7.0, 0, 0}, {0.04, 62.0, 0, 0},   {0.05, 23.0, 0, 0},   {0.025, -12.0, 34, 22},
};
// The quick suite: one building per style, small, each at another resolution and turn.
constexpr Variant kQuickVariants[] = {
    {0.05, 0.0, 30, 20},  {0.03, 30.0, 26, 18}, {0.10, 45.0, 34, 20},
    {0.075, 7.0, 30, 18}, {0.04, 62.0, 30, 22},
};
// The public maps of the quick suite: a warehouse at 0.05 m and an office at 0.068 m.
const char* const kQuickPublicMaps[] = {"mvsim_warehouse", "robotnik_office"};

SuiteWorld Generated(sim::worldgen::BuildingStyle style, const Variant& v, uint64_t seed) {
  SuiteWorld w;
  w.source = WorldSource::kGenerated;
  w.group = sim::worldgen::BuildingStyleName(style);
  w.generated.style = style;
  w.generated.seed = seed;
  w.generated.length_m = v.length_m;
  w.generated.width_m = v.width_m;
  w.generated.render.resolution_m = v.resolution_m;
  w.generated.render.rotation_rad = v.rotation_deg * M_PI / 180.0;
  w.name = "g_" + w.group + "_" + std::to_string(seed);
  return w;
}

// The one map_server YAML in a public map's folder; empty when there is none or several.
std::string MapYamlIn(const fs::path& folder) {
  std::vector<fs::path> yamls;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec))
    if (e.path().extension() == ".yaml") yamls.push_back(e.path());
  return yamls.size() == 1 ? yamls[0].string() : std::string();
}

void AddPublicMaps(const PlanOptions& o, SuitePlan& plan) {
  std::error_code ec;
  if (o.worlds_dir.empty() || !fs::is_directory(o.worlds_dir, ec)) {
    plan.notes.push_back("public maps left out: no folder " +
                         (o.worlds_dir.empty() ? std::string("given") : o.worlds_dir));
    return;
  }
  std::vector<fs::path> folders;
  for (const auto& e : fs::directory_iterator(o.worlds_dir, ec))
    if (e.is_directory()) folders.push_back(e.path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders) {
    const std::string name = folder.filename().string();
    if (o.quick && std::find(std::begin(kQuickPublicMaps), std::end(kQuickPublicMaps), name) ==
                       std::end(kQuickPublicMaps))
      continue;
    SuiteWorld w;
    w.source = WorldSource::kPublic;
    w.group = "public";
    w.name = name;
    w.map_yaml = MapYamlIn(folder);  // none or several: reported as unusable, by name
    plan.worlds.push_back(w);
  }
}

}  // namespace

SuitePlan PlanSuite(const PlanOptions& o) {
  SuitePlan plan;
  uint64_t seed = 100;
  if (o.quick) {
    for (size_t i = 0; i < std::size(kQuickVariants); ++i)
      plan.worlds.push_back(Generated(
          sim::worldgen::AllBuildingStyles()[i % sim::worldgen::AllBuildingStyles().size()],
          kQuickVariants[i], ++seed));
  } else {
    for (const Variant& v : kVariants)
      for (sim::worldgen::BuildingStyle style : sim::worldgen::AllBuildingStyles())
        plan.worlds.push_back(Generated(style, v, ++seed));
  }
  AddPublicMaps(o, plan);
  if (!o.livinglab_scenario.empty()) {
    SuiteWorld w;
    w.source = WorldSource::kLivingLab;
    w.group = "livinglab";
    w.name = "livinglab";
    w.scenario_yaml = o.livinglab_scenario;
    plan.worlds.push_back(w);
  }
  return plan;
}

}  // namespace fleetmap::eval::suite
