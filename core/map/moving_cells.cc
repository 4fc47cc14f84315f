#include "core/map/moving_cells.h"

#include <cassert>

namespace fleetmap::core {

Status MovingCellOptions::Validate() const {
  if (!(occupied_log_odds > 0 && left_log_odds < occupied_log_odds &&
        reported_log_odds < left_log_odds)) {
    return InvalidArgument(
        "moving cells: need occupied_log_odds > 0 and reported_log_odds < left_log_odds < "
        "occupied_log_odds");
  }
  return OkStatus();
}

MovingCells::MovingCells(const GridGeometry& geometry, const MovingCellOptions& options)
    : options_(options), width_(geometry.width()) {
  if (options.enabled) state_.assign(static_cast<size_t>(geometry.num_cells()), 0);
}

int MovingCells::Report(OccupancyGrid& grid) const {
  if (!tracking()) return 0;
  assert(grid.geometry().width() == width_ &&
         static_cast<size_t>(grid.geometry().num_cells()) == state_.size());
  int lowered = 0;
  for (int y = 0; y < grid.geometry().height(); ++y) {
    for (int x = 0; x < width_; ++x) {
      if (!Left({x, y}) || grid.log_odds({x, y}) <= options_.reported_log_odds) continue;
      grid.SetLogOdds({x, y}, options_.reported_log_odds);
      ++lowered;
    }
  }
  return lowered;
}

}  // namespace fleetmap::core
