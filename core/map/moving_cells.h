// Cells something occupied and then left while one grid was being built: a person who walked
// through, turned at the end of a path or stood for a while, a forklift that stopped and
// drove on. A pallet's cells are hit whenever they are seen and are not seen clear once they
// were hit; these were. One map cannot tell a pallet from a person who stands for the whole
// map, but it can tell what moved while it watched: such a cell is reported as free (it was
// last seen clear, and whatever stood there moves), so that no merge adds it and a candidate
// there is dropped (docs/aggregator.md, "People and forklifts"). Summed log-odds alone leave
// such a cell near unknown for many scans after it was left (a clamped "occupied" takes a
// dozen misses to reach 0, more to count as free), and occupied again where the person comes
// back within the map: neither drops a candidate there.
#pragma once

#include <cstdint>
#include <vector>

#include "core/map/occupancy_grid.h"

namespace fleetmap::core {

struct MovingCellOptions {
  bool enabled = true;
  // A cell counts as occupied once its evidence reaches this, log-odds: two hits more than
  // misses (2 x 2.2 - 0.4), the merge's add_min_log_odds; a single stray return does not.
  float occupied_log_odds = 3.0f;
  // ... and as left when its evidence falls back to this afterwards: about eight misses more
  // than hits after it was occupied. A pallet's face, hit by most beams that reach it, never
  // gets there; a cell a person left is crossed by every beam that passes.
  float left_log_odds = 0.0f;
  // The evidence a left cell is reported with, at most (log-odds < left_log_odds): below the
  // merge's remove_max_log_odds (-2.0), so that it counts as seen free there.
  float reported_log_odds = -2.2f;
  Status Validate() const;
};

class MovingCells {
 public:
  MovingCells() = default;
  MovingCells(const GridGeometry& geometry, const MovingCellOptions& options);

  // Called with a cell's evidence after each update of it.
  void Observe(const CellIndex& c, float log_odds) {
    uint8_t& s = state_[static_cast<size_t>(c.y) * width_ + c.x];
    if (log_odds >= options_.occupied_log_odds)
      s |= kOccupied;
    else if ((s & kOccupied) && log_odds <= options_.left_log_odds)
      s |= kLeft;
  }
  bool Left(const CellIndex& c) const {
    return (state_[static_cast<size_t>(c.y) * width_ + c.x] & kLeft) != 0;
  }
  bool tracking() const { return !state_.empty(); }

  // Lowers the evidence of every left cell of `grid` (the geometry given at construction) to
  // reported_log_odds; returns how many cells that changed.
  int Report(OccupancyGrid& grid) const;

 private:
  enum : uint8_t { kOccupied = 1, kLeft = 2 };
  MovingCellOptions options_;
  int width_ = 0;
  std::vector<uint8_t> state_;  // per cell, kOccupied | kLeft
};

}  // namespace fleetmap::core
