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

std::vector<CellChange> PlanHeldConfirmations(const HeldReport& report,
                                              const std::map<int64_t, Candidate>& candidates,
                                              const MergeOptions& options,
                                              const std::vector<uint8_t>* wall_distance,
                                              double resolution_m) {
  std::vector<CellChange> adds;
  if (options.confirmations < 2) return adds;
  // A wall distance of d cells: the nearest wall cell's centre lies d cells away.
  const int clearance = wall_distance ? CellsFor(options.held_wall_clearance_m, resolution_m) : 0;
  for (size_t i = 0;
       i < report.cells.size() && i < report.since_s.size() && i < report.until_s.size(); ++i) {
    const auto it = candidates.find(report.cells[i]);
    if (it == candidates.end()) continue;
    const int64_t cell = report.cells[i];
    if (wall_distance && cell >= 0 && static_cast<size_t>(cell) < wall_distance->size() &&
        (*wall_distance)[static_cast<size_t>(cell)] <= clearance)
      continue;
    const double since = report.since_s[i], until = report.until_s[i];
    const bool long_enough = until - since >= options.confirm_min_gap_s;
    const bool overlaps = since <= it->second.last_seen_end_s && until >= it->second.first.start_s;
    if (long_enough && overlaps) adds.push_back({report.cells[i], CellChangeKind::kAdded});
  }
  std::sort(adds.begin(), adds.end(),
            [](const CellChange& a, const CellChange& b) { return a.cell < b.cell; });
  adds.erase(std::unique(adds.begin(), adds.end(),
                         [](const CellChange& a, const CellChange& b) { return a.cell == b.cell; }),
             adds.end());
  return adds;
}

}  // namespace fleetmap::aggregator
