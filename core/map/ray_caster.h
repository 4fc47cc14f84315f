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
  // `max_clearance_m` > 0 caps the distance field there (a beam then jumps at most that far at
  // once), so that UpdateSolid recomputes only the cells near a change; 0: uncapped.
  explicit RayCaster(const GridGeometry& geometry, double max_clearance_m = 0.0);

  // Sets the solid cells (row-major, non-zero blocks beams) and rebuilds the distance field.
  void SetSolid(std::vector<uint8_t> solid);
  // Sets the cells of `changed` (inside the grid) to `solid_in_window` (row-major in the
  // window): with a capped field only the cells within the cap of the window are recomputed, to
  // the values SetSolid would give; uncapped, the whole field.
  void UpdateSolid(const CellWindow& changed, const std::vector<uint8_t>& solid_in_window);
  const std::vector<uint8_t>& solid() const { return solid_; }
  const GridGeometry& geometry() const { return geometry_; }

  // First solid cell along the ray from `origin` (world) in direction `angle_rad` (world).
  // Beams that leave the grid hit nothing.
  RayHit Cast(const Eigen::Vector2d& origin, double angle_rad, double max_range_m) const;

 private:
  // The distance field of the cells of `out`, from the solid cells within reach of them.
  void Recompute(const CellWindow& out);

  GridGeometry geometry_;
  float max_clearance_cells_;  // +inf when uncapped
  int reach_cells_;            // how far a change of a solid cell moves the capped field
  std::vector<uint8_t> solid_;
  std::vector<float> clearance_cells_;  // distance to the nearest solid cell centre, cells
};

}  // namespace fleetmap::core
