// A small hand-made world for the aggregator tests: a 20 m x 20 m hall at 5 cm with walls,
// a rack, a pillar and a wall stub (lines in both directions), optionally turned as a whole,
// and temporary maps built from ray-cast scans of it at known true poses.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/map/ray_caster.h"
#include "core/map/scan_inserter.h"
#include "core/map/temp_map.h"

namespace fleetmap::aggregator::testing {

constexpr double kRes = 0.05;
constexpr int kHallCells = 400;  // 20 m

struct Box {
  Eigen::Vector2d centre;  // metres, in the hall's own frame
  Eigen::Vector2d size;
};

// Walls 0.15 m thick around the hall, a rack, a pillar, a wall stub.
inline std::vector<Box> HallBoxes() {
  return {{{10.0, 0.075}, {20.0, 0.15}}, {{10.0, 19.925}, {20.0, 0.15}},
          {{0.075, 10.0}, {0.15, 20.0}}, {{19.925, 10.0}, {0.15, 20.0}},
          {{6.0, 14.6}, {6.0, 1.2}},     {{14.0, 6.0}, {0.6, 0.6}},
          {{12.0, 13.0}, {0.15, 6.0}}};
}

// True when the point (hall frame) lies in one of the boxes.
inline bool InBoxes(const std::vector<Box>& boxes, const Eigen::Vector2d& p) {
  for (const Box& b : boxes)
    if (std::abs(p.x() - b.centre.x()) < b.size.x() / 2 &&
        std::abs(p.y() - b.centre.y()) < b.size.y() / 2)
      return true;
  return false;
}

// The hall turned by `yaw_rad` about its centre, in a map frame of the same size: occupied
// inside a box, free elsewhere inside the walls, unknown outside them.
inline core::OccupancyGrid HallMap(double yaw_rad = 0.0, const std::vector<Box>& extra = {}) {
  core::OccupancyGrid grid(core::GridGeometry(kRes, kHallCells, kHallCells));
  std::vector<Box> boxes = HallBoxes();
  boxes.insert(boxes.end(), extra.begin(), extra.end());
  const core::Pose2 to_hall = core::Pose2(10, 10, yaw_rad) * core::Pose2(-10, -10, 0);
  const core::Pose2 from_map = to_hall.Inverse();
  for (int y = 0; y < kHallCells; ++y) {
    for (int x = 0; x < kHallCells; ++x) {
      const Eigen::Vector2d p = from_map.Apply(grid.geometry().CellCenter({x, y}));
      const bool inside = p.x() > 0 && p.y() > 0 && p.x() < 20 && p.y() < 20;
      grid.SetState({x, y}, InBoxes(boxes, p) ? core::CellState::kOccupied
                            : inside          ? core::CellState::kFree
                                              : core::CellState::kUnknown);
    }
  }
  return grid;
}

// A corridor 2 m wide along x (walls at y = 8 and 10 m, `wall_half_m` either side), the whole
// 20 m of the map, with nothing across it: every shift along it fits alike, a shift across it
// does not. Unknown outside its walls.
inline core::OccupancyGrid CorridorMap(double wall_half_m) {
  core::OccupancyGrid grid(core::GridGeometry(kRes, kHallCells, kHallCells));
  for (int y = 0; y < kHallCells; ++y)
    for (int x = 0; x < kHallCells; ++x) {
      const double wy = grid.geometry().CellCenter({x, y}).y();
      grid.SetState({x, y}, std::abs(wy - 8.0) < wall_half_m || std::abs(wy - 10.0) < wall_half_m
                                ? core::CellState::kOccupied
                            : wy > 8.0 && wy < 10.0 ? core::CellState::kFree
                                                    : core::CellState::kUnknown);
    }
  return grid;
}

inline std::vector<uint8_t> Solid(const core::OccupancyGrid& world) {
  std::vector<uint8_t> solid(world.cells().size());
  for (size_t i = 0; i < solid.size(); ++i) solid[i] = world.cells()[i] > 0;
  return solid;
}

// A 270 degree scan of 541 beams (an S300) from `scanner_in_map`, 2 cm range noise.
inline core::LaserScan Scan(const core::RayCaster& caster, const core::Pose2& scanner_in_map,
                            std::mt19937& rng) {
  core::LaserScan scan;
  scan.angle_min_rad = -0.75 * M_PI;
  scan.angle_increment_rad = 0.5 * M_PI / 180;
  scan.range_min_m = 0.05;
  scan.range_max_m = 30.0;
  std::normal_distribution<double> noise(0.0, 0.02);
  for (int i = 0; i < 541; ++i) {
    const core::RayHit hit =
        caster.Cast(scanner_in_map.translation(), scanner_in_map.theta_rad + scan.angle(i), 30.0);
    scan.ranges_m.push_back(std::isfinite(hit.range_m) ? float(hit.range_m + noise(rng))
                                                       : INFINITY);
  }
  return scan;
}

struct TempMapSpec {
  core::Pose2 start;                  // true pose of T in the map
  Eigen::Vector2d step = {0.1, 0.0};  // vehicle motion per scan, in T
  int scans = 30;
  double grid_m = 14.0;  // side of the temporary grid, centred on T
  // The anchor is the start moved by (x_m, y_m) in the map frame and turned by theta_rad.
  core::Pose2 anchor_error;
  std::string vehicle = "v1";
  int32_t sequence = 1;
  double start_s = 0.0, end_s = 10.0;
  uint32_t seed = 7;
};

// A temporary map of `world` (its occupied cells block beams) as a perfect vehicle builds it,
// anchored at the start moved by the anchor error.
inline core::TempMap BuildTempMap(const core::OccupancyGrid& world, const TempMapSpec& spec) {
  core::RayCaster caster(world.geometry());
  caster.SetSolid(Solid(world));
  std::mt19937 rng(spec.seed);
  core::TempMap map;
  map.vehicle_id = spec.vehicle;
  map.sequence = spec.sequence;
  map.start_s = spec.start_s;
  map.end_s = spec.end_s;
  const int cells = static_cast<int>(std::lround(spec.grid_m / kRes));
  map.grid = core::OccupancyGrid(core::GridGeometry(
      kRes, cells, cells, core::Pose2(-spec.grid_m / 2 + 0.013, -spec.grid_m / 2 + 0.031, 0)));
  for (int k = 0; k < spec.scans; ++k) {
    const core::Pose2 in_t(spec.step.x() * k, spec.step.y() * k, 0.0);
    const core::LaserScan scan = Scan(caster, spec.start * in_t, rng);
    core::InsertScan(scan, in_t, {}, map.grid);
  }
  const core::Pose2& e = spec.anchor_error;
  map.anchor_in_map = core::Pose2(spec.start.x_m + e.x_m, spec.start.y_m + e.y_m,
                                  spec.start.theta_rad + e.theta_rad);
  return map;
}

}  // namespace fleetmap::aggregator::testing
