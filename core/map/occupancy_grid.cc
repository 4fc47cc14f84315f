#include "core/map/occupancy_grid.h"

#include <algorithm>

namespace fleetmap::core {

OccupancyGrid::OccupancyGrid(const GridGeometry& geometry, LogOddsLimits limits)
    : geometry_(geometry), limits_(limits) {
  assert(geometry.Validate().ok());
  cells_.assign(static_cast<size_t>(geometry.num_cells()), 0.0f);
}

CellState OccupancyGrid::state(const CellIndex& c, const OccupancyThresholds& t) const {
  return TriStateClassifier(t)(log_odds(c));
}

float OccupancyGrid::CanonicalLogOdds(CellState state) const {
  switch (state) {
    case CellState::kOccupied:
      return limits_.max_log_odds;
    case CellState::kFree:
      return limits_.min_log_odds;
    case CellState::kUnknown:
      break;
  }
  return 0.0f;
}

void OccupancyGrid::SetState(const CellIndex& c, CellState state) {
  cells_[geometry_.Index(c)] = CanonicalLogOdds(state);
}

int64_t OccupancyGrid::CountState(CellState state, const OccupancyThresholds& t) const {
  const TriStateClassifier classify(t);
  return std::count_if(cells_.begin(), cells_.end(), [&](float l) { return classify(l) == state; });
}

TriStateClassifier::TriStateClassifier(const OccupancyThresholds& t)
    : occupied_above_(ProbabilityToLogOdds(t.occupied_probability)),
      free_below_(ProbabilityToLogOdds(t.free_probability)) {}

}  // namespace fleetmap::core
