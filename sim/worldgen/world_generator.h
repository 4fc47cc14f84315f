// A static map from a seed: a building of a style, drawn as SLAM would map it, at a chosen
// resolution and turn (docs/worldgen.md).
#pragma once

#include <cstdint>

#include "sim/worldgen/building_style.h"
#include "sim/worldgen/slam_rendering.h"

namespace fleetmap::sim::worldgen {

struct WorldOptions {
  BuildingStyle style = BuildingStyle::kRackedWarehouse;
  uint64_t seed = 1;
  // The building's size along its length and across; 0 draws each from the style's
  // DefaultSize with the seed. Each side within kMinBuildingSideM and 150 m.
  double length_m = 0.0;
  double width_m = 0.0;
  RenderOptions render;  // resolution, the building's turn in the grid, the SLAM look
  core::Status Validate() const;
};

struct GeneratedWorld {
  FloorPlan plan;
  RenderedMap map;
};

// The same options (seed included) give the same map, cell for cell.
core::Result<GeneratedWorld> GenerateWorld(const WorldOptions& options);

}  // namespace fleetmap::sim::worldgen
