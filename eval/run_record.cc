#include "eval/run_record.h"

namespace fleetmap::eval {

void RunRecord::RecordVersion(const core::OccupancyGrid& current_map) {
  const auto& cells = current_map.cells();
  if (ever_occupied.size() != cells.size()) ever_occupied.assign(cells.size(), 0);
  const core::TriStateClassifier classify;
  for (size_t i = 0; i < cells.size(); ++i)
    ever_occupied[i] |= classify(cells[i]) == core::CellState::kOccupied;
  final_map = current_map;
}

void RunRecord::RecordSeenFreeDrops(const std::vector<int64_t>& cells) {
  const size_t n = final_map.cells().size();
  if (dropped_seen_free.size() != n) dropped_seen_free.assign(n, 0);
  for (int64_t c : cells)
    if (c >= 0 && static_cast<size_t>(c) < n) dropped_seen_free[static_cast<size_t>(c)] = 1;
}

}  // namespace fleetmap::eval
