// The history an aggregator's state folder holds (aggregator/persistence/map_persistence.h): the
// snapshot's commits, then the journal's newer ones, read without writing anything (the
// aggregator cuts a torn journal tail when it opens the folder; this only reports it), and
// any version of the map rebuilt from it.
#pragma once

#include <string>
#include <vector>

#include "aggregator/current_map_store.h"
#include "aggregator/merge_commit.h"

namespace fleetmap::ops::mapctl {

struct StateHistory {
  std::vector<aggregator::MergeCommit> commits;  // versions 1..N, in order
  bool snapshot_found = false;
  uint64_t snapshot_version = 0;
  uint32_t static_fingerprint = 0;  // of the static map the snapshot was made for
  int journal_records = 0;          // newer than the snapshot
  bool torn_tail = false;           // the journal ends in a half-written record (ignored)
  std::string torn_detail;

  uint64_t version() const { return commits.empty() ? 0 : commits.back().version; }
};

// The paths of a state folder's snapshot and journal; NotFound when it holds neither.
struct StateFiles {
  std::string snapshot, journal;
};
core::Result<StateFiles> FindStateFiles(const std::string& folder);

// NotFound when the folder holds neither snapshot nor journal; DataLoss (naming the file and
// the record) for a corrupt snapshot or journal or a gap in the versions.
core::Result<StateHistory> ReadStateHistory(const std::string& folder,
                                            int64_t max_file_bytes = int64_t{1} << 30);

// The map at `version` (<= history.version()): the static map with commits 1..version
// applied. FailedPrecondition when the snapshot was made for another static map, OutOfRange
// for a version the history does not reach, DataLoss when a commit does not apply.
core::Result<aggregator::CurrentMapStore> RebuildStore(
    const core::OccupancyGrid& static_map, const StateHistory& history, uint64_t version,
    const aggregator::StoreOptions& options = {});

}  // namespace fleetmap::ops::mapctl
