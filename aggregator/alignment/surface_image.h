// The cells a laser sees of an occupancy grid, as binary pictures for the Hough transform,
// the line refit and the overlap search. A wall in the static map is several cells thick
// and only its first row is ever hit: its surface cells are the occupied cells with a free
// 4-neighbour. A temporary map holds only what its beams hit, spread by the range noise over
// the cells on both sides of a face; its cells with repeated hits straddle the face and have
// their centre within a fraction of a cell of the static surface row's (docs/aggregator.md,
// "Line features"), whatever the angle of view and the grid's own rotation.
#pragma once

#include <cstdint>
#include <vector>

#include "core/map/occupancy_grid.h"

namespace fleetmap::aggregator {

// A binary picture of a grid, row 0 at the grid's origin (as the grid), 1 = set.
struct BinaryImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // width * height, row-major

  bool at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x] != 0; }
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  int64_t Count() const;
};

// Occupied cells (under `thresholds`) with at least one free 4-neighbour.
BinaryImage SurfaceCells(const core::OccupancyGrid& grid,
                         const core::OccupancyThresholds& thresholds = {});
// Cells whose log-odds reach `min_log_odds`.
BinaryImage CellsAtLeast(const core::OccupancyGrid& grid, float min_log_odds);

}  // namespace fleetmap::aggregator
