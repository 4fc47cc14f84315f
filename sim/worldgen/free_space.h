// Where something of a given size can be on a map: cells at least `clearance_m` from every
// cell that is not free (walls, furniture, unknown space), the largest connected piece of
// them, on a planning grid of about 0.1 m whatever the map's resolution. Routes, people and
// forklifts of generated scenarios are planned in it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/result.h"
#include "sim/worldgen/random.h"

namespace fleetmap::sim::worldgen {

class FreeSpace {
 public:
  // FailedPrecondition when no free cell is that far from everything else.
  static core::Result<FreeSpace> Of(const core::OccupancyGrid& map, double clearance_m);

  double clearance_m() const { return clearance_m_; }
  double area_m2() const;
  // In the largest piece.
  bool Contains(const Eigen::Vector2d& p) const;
  // Every point of the segment in the largest piece.
  bool SegmentInside(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // Metres from p to the nearest cell that is not free (0 outside the map), at least: the
  // planning grid keeps the smallest value of the map's cells it covers.
  double FreeRadiusAt(const Eigen::Vector2d& p) const;
  Eigen::Vector2d RandomPoint(Rng& rng) const;
  // The shortest path through the piece (A*, 8 neighbours, a cost for running close to
  // obstacles so that paths keep to the middle of aisles), as straight legs; empty when
  // either end is outside the piece.
  std::vector<Eigen::Vector2d> Path(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;

 private:
  FreeSpace() = default;
  int Cell(const Eigen::Vector2d& p) const;  // -1 outside the planning grid
  Eigen::Vector2d Centre(int cell) const;

  double clearance_m_ = 0.0;
  core::GridGeometry grid_;  // the planning grid: the map's, with cells about 0.1 m
  double cell_m_ = 0.1;
  int width_ = 0, height_ = 0;
  std::vector<float> free_radius_m_;  // per planning cell
  std::vector<uint8_t> inside_;       // per planning cell: in the largest piece
  std::vector<int> piece_;            // the piece's cells, for random points
};

}  // namespace fleetmap::sim::worldgen
