// Where a grid lies in the world: resolution, size in cells and the pose of the outer
// corner of cell (0, 0) (ROS map_server's "origin", yaw included). Cell (x, y) covers
// [x, x+1) x [y, y+1) in cell units of the grid frame; x grows along the origin's heading.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::core {

struct CellIndex {
  int x = 0;
  int y = 0;
  bool operator==(const CellIndex& o) const { return x == o.x && y == o.y; }
  bool operator!=(const CellIndex& o) const { return !(*this == o); }
};

// A rectangle of cells [x0, x0 + width) x [y0, y0 + height).
struct CellWindow {
  int x0 = 0;
  int y0 = 0;
  int width = 0;
  int height = 0;
  int64_t num_cells() const { return int64_t{width} * height; }
  bool operator==(const CellWindow& o) const {
    return x0 == o.x0 && y0 == o.y0 && width == o.width && height == o.height;
  }
};

// Grids larger than this are refused as absurd (100 million cells, 400 MB of floats):
// a 1 km x 1 km hall at 10 cm is 100 million cells.
constexpr int64_t kMaxGridCells = 100'000'000;

class GridGeometry {
 public:
  GridGeometry() = default;
  GridGeometry(double resolution_m, int width_cells, int height_cells, Pose2 origin = {});

  // Checks resolution > 0 and finite, sizes positive and at most kMaxGridCells in total,
  // origin finite. Outside data must pass this before a grid is allocated.
  Status Validate() const;

  double resolution_m() const { return resolution_m_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int64_t num_cells() const { return int64_t{width_} * height_; }
  const Pose2& origin() const { return origin_; }
  CellWindow full_window() const { return {0, 0, width_, height_}; }
  // `w` grown by `cells` on every side and clipped to the grid (empty if `w` is empty).
  CellWindow Grown(const CellWindow& w, int cells) const;

  bool Contains(const CellIndex& c) const {
    return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_;
  }
  bool Contains(const CellWindow& w) const;
  // Row-major, row 0 at the origin (bottom of the map image).
  int64_t Index(const CellIndex& c) const { return int64_t{c.y} * width_ + c.x; }

  // World point -> continuous cell coordinates (cell (i, j) spans [i, i+1) x [j, j+1)).
  Eigen::Vector2d WorldToGrid(const Eigen::Vector2d& world) const;
  // World point -> the cell containing it (may lie outside the grid; check Contains).
  CellIndex WorldToCell(const Eigen::Vector2d& world) const;
  // Centre of a cell in world coordinates.
  Eigen::Vector2d CellCenter(const CellIndex& c) const;
  // The same geometry, i.e. a grid of one can be copied cell by cell into the other.
  bool operator==(const GridGeometry& o) const;
  std::string ToString() const;

 private:
  double resolution_m_ = 0.05;
  int width_ = 0;
  int height_ = 0;
  Pose2 origin_;
};

// The smallest window holding both (either may be empty).
CellWindow Union(const CellWindow& a, const CellWindow& b);

// A length in cells of `resolution_m`, to a millionth of a cell, so that options in metres give
// the whole cells they mean (0.3 m at 0.05 m are 6 cells, not 5.999...).
inline double MetresInCells(double metres, double resolution_m) {
  return std::round(metres / resolution_m * 1e6) / 1e6;
}

}  // namespace fleetmap::core
