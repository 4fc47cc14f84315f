// Where the current map survives a restart: a folder with `snapshot.fms` (snapshot.h) and
// `journal.fmj` (journal.h). A merge is journaled and fsynced before it is acknowledged;
// every so many merges the snapshot is rewritten and the journal emptied. Restoring applies
// the snapshot's commits, then the journal's newer ones, and checks that the result is the
// map and version the snapshot recorded.
#pragma once

#include <string>

#include "aggregator/current_map_store.h"
#include "aggregator/persistence/journal.h"
#include "aggregator/persistence/state_dir_lock.h"

namespace fleetmap::aggregator {

struct PersistenceOptions {
  int snapshot_every_merges = 100;            // journal records before the next snapshot, >= 1
  int64_t max_file_bytes = int64_t{1} << 30;  // snapshot or journal larger than this is refused
  core::Status Validate() const;
};

struct RestoreReport {
  bool snapshot_found = false;
  uint64_t snapshot_version = 0;
  int journal_records = 0;  // replayed from the journal
  int journal_skipped = 0;  // already in the snapshot (a crash between snapshot and reset)
  bool torn_tail_dropped = false;
  std::string torn_detail;
};

class MapPersistence {
 public:
  static constexpr const char* kSnapshotName = "snapshot.fms";
  static constexpr const char* kJournalName = "journal.fmj";

  // Creates `folder` if needed, locks it (state_dir_lock.h: FailedPrecondition while another
  // process holds it), restores `store` (which must be at version 0, holding the static map
  // the files were written for) and opens the journal for appending.
  static core::Result<MapPersistence> Open(const std::string& folder, CurrentMapStore& store,
                                           const PersistenceOptions& options,
                                           RestoreReport* report = nullptr);

  // Journals one commit, fsynced. IoError: the commit must not be applied or acknowledged.
  core::Status Record(const MergeCommit& commit);
  bool SnapshotDue() const { return records_since_snapshot_ >= options_.snapshot_every_merges; }
  // Writes the snapshot of `store` atomically, then empties the journal.
  core::Status Snapshot(const CurrentMapStore& store);
  const std::string& folder() const { return folder_; }

 private:
  MapPersistence(std::string folder, StateDirLock lock, JournalWriter journal,
                 PersistenceOptions options)
      : folder_(std::move(folder)),
        lock_(std::move(lock)),
        journal_(std::move(journal)),
        options_(options) {}

  std::string folder_;
  StateDirLock lock_;  // released when the persistence is destroyed
  JournalWriter journal_;
  PersistenceOptions options_;
  int records_since_snapshot_ = 0;
};

}  // namespace fleetmap::aggregator
