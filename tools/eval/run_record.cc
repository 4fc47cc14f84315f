#include "tools/eval/run_record.h"

namespace fleetmap::eval {

void RunRecord::RecordVersion(const core::OccupancyGrid& current_map) {
  const auto& cells = current_map.cells();
  if (ever_occupied.size() != cells.size()) ever_occupied.assign(cells.size(), 0);
  const core::TriStateClassifier classify;
  for (size_t i = 0; i < cells.size(); ++i)
    ever_occupied[i] |= classify(cells[i]) == core::CellState::kOccupied;
  final_map = current_map;
}

}  // namespace fleetmap::eval
