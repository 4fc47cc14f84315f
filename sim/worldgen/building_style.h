// The kinds of building the generator draws, each from a seed and a size in metres.
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "sim/worldgen/floor_plan.h"
#include "sim/worldgen/random.h"

namespace fleetmap::sim::worldgen {

enum class BuildingStyle {
  kRackedWarehouse,    // rack rows 1.2 m deep, aisles 2.5 to 4 m, cross aisles, columns, a dock
  kBlockStackingHall,  // open floor, few walls, pallets stacked in blocks with lanes between
  kOffice,             // corridors, rooms with doors, desks and tables, an open-plan end
  kHospital,           // long corridors, ward rooms with wide doors and beds, carts in alcoves
  kMixedHall,          // a slanted and a curved wall, racks at an angle, machines, round columns
};

const std::vector<BuildingStyle>& AllBuildingStyles();
const char* BuildingStyleName(BuildingStyle style);  // "racked_warehouse", ...
core::Result<BuildingStyle> ParseBuildingStyle(const std::string& name);

// Sizes a style is drawn at when none is asked (metres, along x and y of the building).
struct SizeRange {
  double min_length_m, max_length_m, min_width_m, max_width_m;
};
SizeRange DefaultSize(BuildingStyle style);

// Smallest building any style draws (along either side): below it there is no room for
// a vehicle's route beside the furniture.
constexpr double kMinBuildingSideM = 12.0;

FloorPlan DrawBuilding(BuildingStyle style, double length_m, double width_m, Rng& rng);

// One per style (racked_warehouse.cc, ...): each draws into a plan whose length_m and
// width_m are set.
void DrawRackedWarehouse(FloorPlan& plan, Rng& rng);
void DrawBlockStackingHall(FloorPlan& plan, Rng& rng);
void DrawOffice(FloorPlan& plan, Rng& rng);
void DrawHospital(FloorPlan& plan, Rng& rng);
void DrawMixedHall(FloorPlan& plan, Rng& rng);

}  // namespace fleetmap::sim::worldgen
