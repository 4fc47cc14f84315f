#include "aggregator/candidates_seen_free.h"

#include <algorithm>

namespace fleetmap::aggregator {

std::vector<int64_t> CandidateCells(const std::map<int64_t, Candidate>& candidates) {
  std::vector<int64_t> cells;
  cells.reserve(candidates.size());
  for (const auto& entry : candidates) cells.push_back(entry.first);
  return cells;
}

std::vector<CellChange> PlanCandidateDrops(const SeenFreeReport& report,
                                           const std::map<int64_t, Candidate>& candidates) {
  std::vector<int64_t> cells = report.cells;
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  std::vector<CellChange> drops;
  for (int64_t cell : cells) {
    const auto it = candidates.find(cell);
    if (it != candidates.end() && it->second.last_seen_end_s < report.first_pass_s)
      drops.push_back({cell, CellChangeKind::kCandidateDropped});
  }
  return drops;
}

}  // namespace fleetmap::aggregator
