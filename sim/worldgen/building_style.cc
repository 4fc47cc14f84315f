#include "sim/worldgen/building_style.h"

namespace fleetmap::sim::worldgen {

const std::vector<BuildingStyle>& AllBuildingStyles() {
  static const std::vector<BuildingStyle> all = {
      BuildingStyle::kRackedWarehouse, BuildingStyle::kBlockStackingHall, BuildingStyle::kOffice,
      BuildingStyle::kHospital, BuildingStyle::kMixedHall};
  return all;
}

const char* BuildingStyleName(BuildingStyle style) {
  switch (style) {
    case BuildingStyle::kRackedWarehouse:
      return "racked_warehouse";
    case BuildingStyle::kBlockStackingHall:
      return "block_stacking_hall";
    case BuildingStyle::kOffice:
      return "office";
    case BuildingStyle::kHospital:
      return "hospital";
    case BuildingStyle::kMixedHall:
      return "mixed_hall";
  }
  return "?";
}

core::Result<BuildingStyle> ParseBuildingStyle(const std::string& name) {
  std::string known;
  for (BuildingStyle s : AllBuildingStyles()) {
    if (name == BuildingStyleName(s)) return s;
    known += std::string(known.empty() ? "" : ", ") + BuildingStyleName(s);
  }
  return core::InvalidArgument("unknown building style '" + name + "' (known: " + known + ")");
}

SizeRange DefaultSize(BuildingStyle style) {
  switch (style) {
    case BuildingStyle::kRackedWarehouse:
      return {40, 120, 30, 80};
    case BuildingStyle::kBlockStackingHall:
      return {30, 100, 25, 60};
    case BuildingStyle::kOffice:
      return {25, 70, 15, 35};
    case BuildingStyle::kHospital:
      return {60, 150, 15, 30};
    case BuildingStyle::kMixedHall:
      return {30, 80, 20, 50};
  }
  return {30, 60, 20, 40};
}

FloorPlan DrawBuilding(BuildingStyle style, double length_m, double width_m, Rng& rng) {
  using Draw = void (*)(FloorPlan&, Rng&);
  Draw draw = DrawRackedWarehouse;
  switch (style) {
    case BuildingStyle::kRackedWarehouse:
      draw = DrawRackedWarehouse;
      break;
    case BuildingStyle::kBlockStackingHall:
      draw = DrawBlockStackingHall;
      break;
    case BuildingStyle::kOffice:
      draw = DrawOffice;
      break;
    case BuildingStyle::kHospital:
      draw = DrawHospital;
      break;
    case BuildingStyle::kMixedHall:
      draw = DrawMixedHall;
      break;
  }
  FloorPlan plan;
  plan.style = BuildingStyleName(style);
  plan.length_m = length_m;
  plan.width_m = width_m;
  draw(plan, rng);
  return plan;
}

}  // namespace fleetmap::sim::worldgen
