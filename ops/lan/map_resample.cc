#include "ops/lan/map_resample.h"

#include <algorithm>
#include <cassert>

namespace fleetmap::ops::lan {

core::OccupancyGrid ResampleMap(const core::OccupancyGrid& fine, int factor) {
  assert(factor >= 1);
  const core::GridGeometry& g = fine.geometry();
  const core::GridGeometry coarse_geometry(g.resolution_m() * factor,
                                           (g.width() + factor - 1) / factor,
                                           (g.height() + factor - 1) / factor, g.origin());
  core::OccupancyGrid coarse(coarse_geometry, fine.limits());
  for (int cy = 0; cy < coarse_geometry.height(); ++cy) {
    for (int cx = 0; cx < coarse_geometry.width(); ++cx) {
      int occupied = 0, free = 0, cells = 0;
      for (int y = cy * factor; y < std::min(g.height(), (cy + 1) * factor); ++y) {
        for (int x = cx * factor; x < std::min(g.width(), (cx + 1) * factor); ++x) {
          const core::CellState s = fine.state({x, y});
          occupied += s == core::CellState::kOccupied;
          free += s == core::CellState::kFree;
          ++cells;
        }
      }
      const core::CellState s = occupied > 0        ? core::CellState::kOccupied
                                : 2 * free >= cells ? core::CellState::kFree
                                                    : core::CellState::kUnknown;
      coarse.SetState({cx, cy}, s);
    }
  }
  return coarse;
}

}  // namespace fleetmap::ops::lan
