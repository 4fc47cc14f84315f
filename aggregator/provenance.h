// The history of the current map: every changed cell with the merge that changed it, so it
// answers "what changed where, when, seen by whom". Kept in commit order; the commits are
// also what the snapshot stores (see snapshot.h).
#pragma once

#include <unordered_map>
#include <vector>

#include "aggregator/merge_commit.h"

namespace fleetmap::aggregator {

struct CellEvent {
  int64_t cell = 0;
  uint64_t version = 0;  // the map version the change created
  CellChangeKind kind = CellChangeKind::kAdded;
  // Owned by the log; valid until the log records the next commit or is destroyed.
  const ChangeSource* source = nullptr;
};

class ProvenanceLog {
 public:
  void Record(MergeCommit commit);

  // Every change of one cell, oldest first.
  std::vector<CellEvent> HistoryOf(int64_t cell) const;
  // Every change merged at a time in [from_s, to_s], in commit order.
  std::vector<CellEvent> ChangesBetween(double from_s, double to_s) const;
  // Every change a vehicle's temporary maps made, in commit order.
  std::vector<CellEvent> ChangesSeenBy(const std::string& vehicle_id) const;

  const std::vector<MergeCommit>& commits() const { return commits_; }
  size_t num_changes() const { return num_changes_; }

 private:
  CellEvent Event(size_t commit, size_t change) const;

  std::vector<MergeCommit> commits_;
  // Per changed cell: (commit, change) positions, oldest first.
  std::unordered_map<int64_t, std::vector<std::pair<uint32_t, uint32_t>>> by_cell_;
  size_t num_changes_ = 0;
};

}  // namespace fleetmap::aggregator
