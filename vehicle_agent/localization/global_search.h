// Global localization's first step: where on the whole map does one scan fit? A branch-and-
// bound search over position and heading (the correlative scan matching of Olson 2009 made
// fast by Hess et al. 2016, "Real-Time Loop Closure in 2D LIDAR SLAM", the method of
// Cartographer's fast correlative scan matcher). Each scan end point scores how close it lies
// to a mapped obstacle (1 on one, falling off over sigma_m); a node of the search stands for
// 2^h x 2^h positions at one heading, and its bound is the score on a grid that holds, per
// cell, the best of the 2^h x 2^h cells the node stands for, so whole regions of the map are
// dropped at once without missing the best pose. Returns the best poses that are distinct,
// for the particle filter to start from: in a building of repeated aisles one scan cannot
// tell which aisle it is in; driving can.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/result.h"

namespace fleetmap::vehicle_agent {

struct GlobalSearchOptions {
  double resolution_m = 0.1;        // positions searched, m, > 0 (at least the map's)
  double sigma_m = 0.15;            // an end point this far from an obstacle scores 0.61, m, > 0
  int max_points = 120;             // end points used, spread over the scan, >= 3
  double max_point_range_m = 20.0;  // end points further from the vehicle are left out, m, > 0
  // Heading step, rad; 0: the angle that moves the furthest point used by one search cell.
  double angle_step_rad = 0.0;
  int levels = 7;              // the coarsest node is 2^(levels-1) cells wide, 1..12
  int max_candidates = 32;     // distinct poses returned at most, >= 1
  double min_score = 0.55;     // mean end-point score a pose needs, [0, 1]
  double distinct_m = 1.0;     // candidates closer than this in position ...
  double distinct_rad = 0.35;  // ... and heading are one, the better kept
  core::Status Validate() const;
};

struct GlobalCandidate {
  core::Pose2 base_in_map;
  double score = 0.0;  // mean end-point score, [0, 1]
};

class GlobalSearch {
 public:
  // Precomputes the search grids of `map` (options must pass Validate()).
  GlobalSearch(const core::OccupancyGrid& map, const GlobalSearchOptions& options);

  // The best distinct poses of the vehicle whose scan has these end points (vehicle frame,
  // m), best first; only poses on free cells, each scoring at least min_score. Empty when
  // none does, or with fewer than 3 points.
  std::vector<GlobalCandidate> Search(const std::vector<Eigen::Vector2f>& points_in_base) const;
  // The score Search gives the vehicle at `base_in_map` (the same points, the finest grid):
  // how a pose the filter holds compares with what the search finds. 0 with fewer than 3 points.
  double Score(const std::vector<Eigen::Vector2f>& points_in_base,
               const core::Pose2& base_in_map) const;

  int levels() const { return static_cast<int>(grids_.size()); }

 private:
  struct Grid {
    int pad = 0;  // cells before index 0 on each axis: a window may start left of the map
    int width = 0, height = 0;
    std::vector<uint8_t> value;  // 0..255
    int At(int x, int y) const {
      const int gx = x + pad, gy = y + pad;
      if (gx < 0 || gy < 0 || gx >= width || gy >= height) return 0;
      return value[static_cast<size_t>(gy) * width + gx];
    }
  };
  struct Node;

  void BuildScoreGrid(const core::OccupancyGrid& map);
  void BuildCoarserGrids();

  GlobalSearchOptions options_;
  core::Pose2 origin_;  // the map's grid origin
  double cell_m_ = 0.1;
  int width_ = 0, height_ = 0;  // search cells
  std::vector<uint8_t> free_;   // per search cell: the vehicle may stand there
  std::vector<Grid> grids_;     // level h: the best over 2^h x 2^h cells from (x, y) on
};

}  // namespace fleetmap::vehicle_agent
