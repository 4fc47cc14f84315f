// Occupancy probability at any point of a grid, bilinearly interpolated between cell centres,
// with its gradient: what Gauss-Newton scan matching descends (hector_slam's OccGridMapUtil).
// Never-observed cells count as probability 0, so unexplored space does not attract points.
#pragma once

#include <Eigen/Core>
#include <array>

#include "core/occupancy_grid.h"

namespace fleetmap::vehicle_agent {

struct InterpolatedValue {
  double value = 0.0;              // occupancy probability in [0, 1]
  Eigen::Vector2d gradient_per_m;  // d value / d (x, y), per metre in the grid's frame
};

class MapInterpolator {
 public:
  explicit MapInterpolator(const core::OccupancyGrid* grid);  // `grid` outlives this
  // `p` in the frame the grid's geometry is expressed in (origin yaw must be 0).
  InterpolatedValue At(const Eigen::Vector2d& p) const;
  // At(p).value alone (the same number), for searches that need no gradient.
  double Value(const Eigen::Vector2d& p) const;

 private:
  double Probability(int x, int y) const;  // 0 outside the grid
  double FromLogOdds(float log_odds) const;
  struct Corners {
    double fx, fy;              // position between the cell centres, [0, 1)
    double p00, p10, p01, p11;  // probabilities of the four cells around it
  };
  Corners CornersAt(const Eigen::Vector2d& p) const;

  const core::OccupancyGrid* grid_;
  // log-odds -> probability, sampled over the grid's clamping range (exp per lookup would be
  // the matcher's hottest cost); shared by every interpolator over the same limits.
  const std::array<float, 1024>* table_;
  float table_min_, table_scale_;
};

}  // namespace fleetmap::vehicle_agent
