#include "vehicle_agent/localization/short_beam.h"

#include <algorithm>

namespace fleetmap::vehicle_agent {

bool EndsShortInFreeSpace(const core::OccupancyGrid& map, const LikelihoodField& field,
                          const Eigen::Vector2d& from, const Eigen::Vector2d& end,
                          double margin_m) {
  const core::GridGeometry& g = map.geometry();
  const core::CellIndex end_cell = g.WorldToCell(end);
  if (!g.Contains(end_cell) || map.state(end_cell) != core::CellState::kFree) return false;
  const Eigen::Vector2d beam = end - from;
  const double length = beam.norm() - margin_m;
  if (length <= 0) return true;
  const Eigen::Vector2d direction = beam / beam.norm();
  const double half_cell = 0.5 * g.resolution_m();
  for (double d = 0.0; d < length;) {
    const Eigen::Vector2d p = from + direction * d;
    const core::CellIndex cell = g.WorldToCell(p);
    if (g.Contains(cell) && map.state(cell) == core::CellState::kOccupied) return false;
    // The nearest obstacle's surface is at least this far from p in every direction, so
    // nothing on the beam before it can be occupied; a cell's width less, for the cell
    // centres the distances are measured from.
    d += std::max(field.DistanceAt(p) - 2.0 * half_cell, half_cell);
  }
  return true;
}

}  // namespace fleetmap::vehicle_agent
