// Casts laser beams against a raster of solid cells. Far from obstacles a beam jumps ahead by
// the distance to the nearest solid cell (a distance field, recomputed only when the solid
// cells change); near them it walks cell by cell (Amanatides and Woo), so the hit distance is
// the exact entry into the first solid cell.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/map/grid_geometry.h"

namespace fleetmap::core {

constexpr double kNoHit = std::numeric_limits<double>::infinity();

struct RayHit {
  double range_m = kNoHit;  // kNoHit when nothing solid lies within the range
  CellIndex cell;           // the solid cell hit (valid when range_m is finite)
};

class RayCaster {
 public:
  explicit RayCaster(const GridGeometry& geometry);

  // Sets the solid cells (row-major, non-zero blocks beams) and rebuilds the distance field.
  void SetSolid(std::vector<uint8_t> solid);
  const std::vector<uint8_t>& solid() const { return solid_; }
  const GridGeometry& geometry() const { return geometry_; }

  // First solid cell along the ray from `origin` (world) in direction `angle_rad` (world).
  // Beams that leave the grid hit nothing.
  RayHit Cast(const Eigen::Vector2d& origin, double angle_rad, double max_range_m) const;

 private:
  GridGeometry geometry_;
  std::vector<uint8_t> solid_;
  std::vector<float> clearance_cells_;  // distance to the nearest solid cell centre, cells
};

}  // namespace fleetmap::core
