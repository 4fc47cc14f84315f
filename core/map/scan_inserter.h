// Writes one laser scan into an occupancy grid as log-odds evidence: the cell of each return
// gains the hit evidence, every cell the beam crossed before it gains the miss evidence. The
// free space is what lets a merge remove a pallet that was taken away. Values follow
// hector_slam's defaults (hit probability 0.9, miss 0.4).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/map/moving_cells.h"
#include "core/map/occupancy_grid.h"
#include "core/scan.h"

namespace fleetmap::core {

struct ScanInsertOptions {
  float hit_log_odds = 2.197f;    // ln(0.9 / 0.1): evidence for the cell of a return
  float miss_log_odds = -0.405f;  // ln(0.4 / 0.6): evidence for each cell crossed
  double max_range_m = 30.0;      // returns farther than this are not inserted at all
  // Beams with no return clear this far (0: not at all). Safe only where "no return" really
  // means open space, so off by default.
  double no_return_free_m = 0.0;
  int beam_step = 1;  // insert every n-th beam (1: all)
  Status Validate() const;
};

struct InsertStats {
  int hits = 0;          // returns inserted
  int skipped = 0;       // invalid returns, beyond max_range_m, or outside the grid
  int cells_missed = 0;  // free-space updates
};

// `scanner_in_grid` is the scanner pose in the frame the grid's geometry is expressed in.
// Cells outside the grid are ignored: beams are clipped to it.
InsertStats InsertScan(const LaserScan& scan, const Pose2& scanner_in_grid,
                       const ScanInsertOptions& options, OccupancyGrid& grid);

// The same with each beam's unit vector in the grid's frame given (BeamDirections), for one
// scan inserted at one pose into several grids, the levels of a multi-resolution map.
// `moving` (optional, of the grid's geometry) observes every cell updated.
InsertStats InsertScan(const LaserScan& scan, const Pose2& scanner_in_grid,
                       const ScanInsertOptions& options,
                       const std::vector<Eigen::Vector2d>& beam_directions, OccupancyGrid& grid,
                       MovingCells* moving = nullptr);

// (cos, sin) of every beam's angle in the grid's frame, for a scanner heading `theta_rad`.
std::vector<Eigen::Vector2d> BeamDirections(const LaserScan& scan, double theta_rad);

}  // namespace fleetmap::core
