// A floor plan drawn into an occupancy grid the way a SLAM map shows a building, not the way
// a drawing does: walls slightly bent and ragged, their far side and the inside of solid
// things unknown (a laser only sees surfaces), stretches of wall never seen (gaps), obstacles
// a little thicker than they are, speckle, and unknown space all around the building. The
// building may be turned by any angle in the grid, as real maps often are.
#pragma once

#include "core/map/occupancy_grid.h"
#include "core/pose2.h"
#include "core/result.h"
#include "sim/worldgen/floor_plan.h"
#include "sim/worldgen/random.h"

namespace fleetmap::sim::worldgen {

struct SlamLookOptions {
  double margin_m = 1.5;            // unknown border around the building
  double wall_bend_per_m = 0.0015;  // sideways bend of a wall per metre of its length ...
  double wall_bend_max_m = 0.12;    // ... at most this (SLAM's slow drift along a long wall)
  double wall_jitter_m = 0.01;      // sideways noise of a wall every metre along it
  double gaps_per_m = 1.0 / 15.0;   // unseen stretches per metre of inner wall (half on outer)
  double gap_min_m = 0.1, gap_max_m = 0.5;
  double thicken_max_m = 0.06;    // obstacles up to this much thicker than one cell
  double ragged_fraction = 0.15;  // share of an obstacle's face bumped a cell into the room
  double speckle_per_m2 = 0.005;  // lone occupied cells in free space
  core::Status Validate() const;
};

struct RenderOptions {
  double resolution_m = 0.05;
  double rotation_rad = 0.0;  // the building's turn in the grid
  SlamLookOptions look;
  core::Status Validate() const;
};

struct RenderedMap {
  core::OccupancyGrid grid;     // origin (0, 0, 0): the building is turned inside the grid
  core::Pose2 building_in_map;  // building frame -> map frame
};

// Errors: options out of range, or a grid larger than core::kMaxGridCells.
core::Result<RenderedMap> RenderFloorPlan(const FloorPlan& plan, const RenderOptions& options,
                                          Rng& rng);

}  // namespace fleetmap::sim::worldgen
