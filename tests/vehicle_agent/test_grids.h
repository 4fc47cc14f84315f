// Small hand-made grids and scans with known answers for the likelihood tests.
#pragma once

#include <cmath>
#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/map/ray_caster.h"
#include "core/scan.h"
#include "vehicle_agent/localization/scan_endpoints.h"

namespace fleetmap::vehicle_agent::test_grids {

// A free 10 m x 6 m room at 5 cm, walls of `wall_cells` cells (0.05 m each) around it.
inline core::OccupancyGrid Room(int wall_cells = 1, core::Pose2 origin = {}) {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 200, 120, origin));
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 200; ++x) {
      const bool wall =
          x < wall_cells || y < wall_cells || x >= 200 - wall_cells || y >= 120 - wall_cells;
      grid.SetState({x, y}, wall ? core::CellState::kOccupied : core::CellState::kFree);
    }
  }
  return grid;
}

// Marks the cells of the axis-aligned box [x0, x1) x [y0, y1) (metres, grid frame) occupied.
inline void AddBox(core::OccupancyGrid& grid, double x0, double y0, double x1, double y1) {
  const double r = grid.geometry().resolution_m();
  for (int y = int(y0 / r); y < int(y1 / r); ++y)
    for (int x = int(x0 / r); x < int(x1 / r); ++x)
      grid.SetState({x, y}, core::CellState::kOccupied);
}

// A noise-free 360-beam full-circle scan of `grid` from `scanner_in_map` (no return: +inf).
inline core::LaserScan PerfectScan(const core::OccupancyGrid& grid,
                                   const core::Pose2& scanner_in_map, int beams = 360) {
  core::RayCaster caster(grid.geometry());
  std::vector<uint8_t> solid(grid.cells().size());
  for (size_t i = 0; i < solid.size(); ++i) solid[i] = grid.cells()[i] > 0;
  caster.SetSolid(solid);
  core::LaserScan scan;
  scan.angle_min_rad = -M_PI;
  scan.angle_increment_rad = 2 * M_PI / beams;
  scan.range_min_m = 0.05;
  scan.range_max_m = 30.0;
  for (int i = 0; i < beams; ++i) {
    const double a = scanner_in_map.theta_rad + scan.angle(size_t(i));
    const double r = caster.Cast(scanner_in_map.translation(), a, 30.0).range_m;
    scan.ranges_m.push_back(r < 30.0 ? float(r) : INFINITY);
  }
  return scan;
}

// The end points (vehicle frame) of PerfectScan seen from `base_in_map`, at most `max_beams`.
inline std::vector<Eigen::Vector2f> EndpointsSeenFrom(const core::OccupancyGrid& map,
                                                      const core::Pose2& base_in_map,
                                                      int max_beams) {
  const core::LaserScan scan = PerfectScan(map, base_in_map);
  std::vector<Eigen::Vector2f> points;
  ScanEndpoints(scan, core::Pose2(), max_beams, 30.0, points);
  return points;
}

}  // namespace fleetmap::vehicle_agent::test_grids
