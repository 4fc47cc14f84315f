// What the aggregator computes once per static map and reuses for every temporary map: its
// line segments, the building's two dominant directions, and the two overlap scores the
// alignment searches with: the paper's (does a cell land on an occupied static cell?) and
// ours (a smooth field that falls off with the distance to the nearest static surface
// cell, sampled every half cell, so that a shift can be found to a fraction of a cell).
#pragma once

#include <vector>

#include "aggregator/alignment/dominant_directions.h"
#include "aggregator/alignment/line_features.h"

namespace fleetmap::aggregator {

struct StaticFeatureOptions {
  LineFeatureOptions lines = StaticLineOptions();
  DominantDirectionOptions directions;
  // Width of the surface field's Gaussian, cells, > 0: of the grid's quantisation (a surface
  // cell's position is known to a cell), as is the shift below.
  double field_sigma_cells = 1.0;
  // Where a temporary map's hits on a face centre, relative to the static surface row's
  // centre, towards free space, cells [0, 0.5]. Hits straddle the face, and the temporary
  // grid's phase against the face decides whether their cells centre on the face (+0.5) or
  // on the surface row (0); over all phases, a quarter cell. Static lines and the surface
  // field are moved by this much (docs/aggregator.md has the measurement).
  double surface_shift_cells = 0.25;
  core::Status Validate() const;
};

class StaticMapFeatures {
 public:
  static core::Result<StaticMapFeatures> Compute(const core::OccupancyGrid& static_map,
                                                 const StaticFeatureOptions& options = {});

  const core::GridGeometry& geometry() const { return geometry_; }
  const std::vector<LineSegment>& lines() const { return lines_; }  // static frame, metres
  const DominantDirections& directions() const { return directions_; }
  int raw_segments() const { return raw_segments_; }

  // exp(-d^2 / 2 sigma^2), d the distance (cells) from the point to the nearest surface
  // cell's span from its centre to its face on the free side (surface_image.h), bilinear
  // between half-cell nodes; 0 outside the map. Point in the static frame.
  double SurfaceField(const Eigen::Vector2d& point_in_map) const;
  // The paper's overlap test: the cell containing the point is occupied in the static map.
  bool OnOccupied(const Eigen::Vector2d& point_in_map) const;

 private:
  StaticMapFeatures() = default;
  // Continuous cell coordinates of a static-frame point (the geometry's WorldToGrid, with the
  // inverse origin precomputed: this runs for every point of every shift the search tries).
  Eigen::Vector2d GridPoint(const Eigen::Vector2d& point_in_map) const {
    return to_grid_rotation_ * point_in_map + to_grid_offset_;
  }

  core::GridGeometry geometry_;
  std::vector<LineSegment> lines_;
  DominantDirections directions_;
  int raw_segments_ = 0;
  std::vector<float> field_;       // per node: nodes every half cell, (2w+1) x (2h+1)
  std::vector<uint8_t> occupied_;  // per cell
  Eigen::Matrix2d to_grid_rotation_ = Eigen::Matrix2d::Identity();
  Eigen::Vector2d to_grid_offset_ = Eigen::Vector2d::Zero();
};

}  // namespace fleetmap::aggregator
