// An occupancy grid of clamped log-odds cells: the static map, the current map and every
// temporary map are one of these. 0 means never observed (unknown).
#pragma once

#include <algorithm>
#include <vector>

#include "core/map/grid_geometry.h"
#include "core/map/log_odds.h"

namespace fleetmap::core {

class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  // All cells unknown. The geometry must be valid (callers validate outside data first).
  explicit OccupancyGrid(const GridGeometry& geometry, LogOddsLimits limits = {});

  const GridGeometry& geometry() const { return geometry_; }
  const LogOddsLimits& limits() const { return limits_; }

  float log_odds(const CellIndex& c) const { return cells_[geometry_.Index(c)]; }
  // Stores `value` clamped to the limits.
  void SetLogOdds(const CellIndex& c, float value) {
    cells_[geometry_.Index(c)] = std::clamp(value, limits_.min_log_odds, limits_.max_log_odds);
  }
  // Adds evidence (positive: occupied, negative: free), clamped. The Bayes update in log form.
  // Inline: map updates call it for every cell every beam crosses.
  void AddLogOdds(const CellIndex& c, float delta) {
    float& cell = cells_[geometry_.Index(c)];
    cell = std::clamp(cell + delta, limits_.min_log_odds, limits_.max_log_odds);
  }
  double probability(const CellIndex& c) const { return LogOddsToProbability(log_odds(c)); }

  CellState state(const CellIndex& c, const OccupancyThresholds& t = {}) const;
  // Writes the canonical value of a state: occupied = max, free = min, unknown = 0.
  void SetState(const CellIndex& c, CellState state);
  float CanonicalLogOdds(CellState state) const;

  int64_t CountState(CellState state, const OccupancyThresholds& t = {}) const;

  // Row-major cells, row 0 at the origin. For bulk algorithms (codec, rendering).
  const std::vector<float>& cells() const { return cells_; }
  std::vector<float>& mutable_cells() { return cells_; }

 private:
  GridGeometry geometry_;
  LogOddsLimits limits_;
  std::vector<float> cells_;
};

// Tri-state of a log-odds value under thresholds, without a grid (for bulk loops).
class TriStateClassifier {
 public:
  explicit TriStateClassifier(const OccupancyThresholds& t = {});
  CellState operator()(float log_odds) const {
    if (log_odds > occupied_above_) return CellState::kOccupied;
    if (log_odds < free_below_) return CellState::kFree;
    return CellState::kUnknown;
  }

 private:
  float occupied_above_;
  float free_below_;
};

}  // namespace fleetmap::core
