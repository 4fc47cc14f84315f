#include "aggregator/provenance.h"

namespace fleetmap::aggregator {

void ProvenanceLog::Record(MergeCommit commit) {
  const uint32_t index = static_cast<uint32_t>(commits_.size());
  for (uint32_t k = 0; k < commit.changes.size(); ++k)
    by_cell_[commit.changes[k].cell].emplace_back(index, k);
  num_changes_ += commit.changes.size();
  commits_.push_back(std::move(commit));
}

CellEvent ProvenanceLog::Event(size_t commit, size_t change) const {
  const MergeCommit& c = commits_[commit];
  return {c.changes[change].cell, c.version, c.changes[change].kind, &c.source};
}

std::vector<CellEvent> ProvenanceLog::HistoryOf(int64_t cell) const {
  std::vector<CellEvent> events;
  const auto it = by_cell_.find(cell);
  if (it == by_cell_.end()) return events;
  for (const auto& [commit, change] : it->second) events.push_back(Event(commit, change));
  return events;
}

std::vector<CellEvent> ProvenanceLog::ChangesBetween(double from_s, double to_s) const {
  std::vector<CellEvent> events;
  for (size_t c = 0; c < commits_.size(); ++c) {
    const double t = commits_[c].source.merged_s;
    if (t < from_s || t > to_s) continue;
    for (size_t k = 0; k < commits_[c].changes.size(); ++k) events.push_back(Event(c, k));
  }
  return events;
}

std::vector<CellEvent> ProvenanceLog::ChangesSeenBy(const std::string& vehicle_id) const {
  std::vector<CellEvent> events;
  for (size_t c = 0; c < commits_.size(); ++c) {
    if (commits_[c].source.vehicle_id != vehicle_id) continue;
    for (size_t k = 0; k < commits_[c].changes.size(); ++k) events.push_back(Event(c, k));
  }
  return events;
}

}  // namespace fleetmap::aggregator
