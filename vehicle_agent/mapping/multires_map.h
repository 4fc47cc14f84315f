// Hector's multi-resolution occupancy map: the same area at several resolutions, each half
// the one before. Matching starts on the coarsest level, whose wide basins forgive a poor
// initial guess, and is refined level by level (Kohlbrecher et al. 2011).
#pragma once

#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/map/scan_inserter.h"

namespace fleetmap::vehicle_agent {

struct MultiResolutionMapOptions {
  double resolution_m = 0.05;      // finest level
  int levels = 3;                  // 1..5; level i has resolution_m * 2^i
  double size_m = 20.0;            // side of the square area covered
  core::ScanInsertOptions insert;  // hit/miss evidence (hector: 0.9 / 0.4)
  core::MovingCellOptions moving;  // what moved on the finest level (core/map/moving_cells.h)
  core::Status Validate() const;
};

class MultiResolutionMap {
 public:
  // The area is centred on `center_m` (a point in the map's own frame).
  MultiResolutionMap(const MultiResolutionMapOptions& options,
                     const Eigen::Vector2d& center_m = Eigen::Vector2d::Zero());

  int levels() const { return static_cast<int>(levels_.size()); }
  const core::OccupancyGrid& level(int i) const { return levels_[static_cast<size_t>(i)]; }
  const core::OccupancyGrid& finest() const { return levels_.front(); }
  // The finest level's cells that something occupied and then left.
  const core::MovingCells& moving() const { return moving_; }

  // Inserts the scan into every level. `scanner_in_map` is in the map's own frame.
  void Insert(const core::LaserScan& scan, const core::Pose2& scanner_in_map);
  // True when `p` lies at least `margin_m` inside the covered area.
  bool Inside(const Eigen::Vector2d& p, double margin_m) const;

 private:
  MultiResolutionMapOptions options_;
  std::vector<core::OccupancyGrid> levels_;
  core::MovingCells moving_;
};

}  // namespace fleetmap::vehicle_agent
