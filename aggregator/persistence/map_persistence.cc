#include "aggregator/persistence/map_persistence.h"

#include <filesystem>

#include "aggregator/persistence/snapshot.h"

namespace fleetmap::aggregator {
namespace {

core::Status RestoreSnapshot(const std::string& path, CurrentMapStore& store, int64_t max_bytes,
                             RestoreReport& report) {
  auto snapshot = ReadSnapshot(path, max_bytes);
  if (snapshot.status().code() == core::StatusCode::kNotFound) return core::OkStatus();
  if (!snapshot.ok()) return snapshot.status();
  if (snapshot->static_fingerprint != MapFingerprint(store.static_map()))
    return core::FailedPrecondition(path + ": made for another static map");
  for (MergeCommit& c : snapshot->commits) {
    auto applied = store.Apply(std::move(c));
    if (!applied.ok()) return core::DataLoss(path + ": " + applied.status().message());
  }
  if (store.version() != snapshot->version ||
      MapFingerprint(store.current_map()) != snapshot->map_fingerprint) {
    return core::DataLoss(path + ": rebuilt map does not match the snapshot");
  }
  report.snapshot_found = true;
  report.snapshot_version = snapshot->version;
  return core::OkStatus();
}

core::Result<JournalContents> ReplayJournal(const std::string& path, CurrentMapStore& store,
                                            int64_t max_bytes, RestoreReport& report) {
  auto journal = ReadJournal(path, max_bytes);
  if (journal.status().code() == core::StatusCode::kNotFound) return JournalContents{};
  if (!journal.ok()) return journal.status();
  report.torn_tail_dropped = journal->torn_tail;
  report.torn_detail = journal->torn_detail;
  for (size_t i = 0; i < journal->records.size(); ++i) {
    const auto& bytes = journal->records[i];
    auto commit = DecodeCommit(bytes.data(), bytes.size());
    if (!commit.ok()) return commit.status().WithContext(path + " record " + std::to_string(i));
    if (commit->version <= store.version()) {
      ++report.journal_skipped;
      continue;
    }
    auto applied = store.Apply(std::move(commit).value());
    if (!applied.ok()) return core::DataLoss(path + ": " + applied.status().message());
    ++report.journal_records;
  }
  return journal;
}

}  // namespace

core::Status PersistenceOptions::Validate() const {
  if (snapshot_every_merges < 1)
    return core::InvalidArgument("persistence.snapshot_every_merges must be >= 1");
  if (max_file_bytes < 1024)
    return core::InvalidArgument("persistence.max_file_bytes must be >= 1024");
  return core::OkStatus();
}

core::Result<MapPersistence> MapPersistence::Open(const std::string& folder, CurrentMapStore& store,
                                                  const PersistenceOptions& options,
                                                  RestoreReport* report) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  if (store.version() != 0) return core::FailedPrecondition("restore needs a fresh store");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return core::IoError(folder + ": cannot create the folder: " + ec.message());
  auto lock = StateDirLock::Acquire(folder);
  if (!lock.ok()) return lock.status();
  RestoreReport local;
  RestoreReport& r = report ? *report : local;
  r = RestoreReport();
  const std::string journal_path = folder + "/" + kJournalName;
  FLEETMAP_RETURN_IF_ERROR(
      RestoreSnapshot(folder + "/" + kSnapshotName, store, options.max_file_bytes, r));
  JournalContents found;
  FLEETMAP_ASSIGN_OR_RETURN(found, ReplayJournal(journal_path, store, options.max_file_bytes, r));
  auto writer = JournalWriter::Open(journal_path, found);
  if (!writer.ok()) return writer.status();
  MapPersistence persistence(folder, std::move(lock).value(), std::move(writer).value(), options);
  persistence.records_since_snapshot_ = r.journal_records + r.journal_skipped;
  return persistence;
}

core::Status MapPersistence::Record(const MergeCommit& commit) {
  FLEETMAP_RETURN_IF_ERROR(journal_.Append(EncodeCommit(commit)));
  ++records_since_snapshot_;
  return core::OkStatus();
}

core::Status MapPersistence::Snapshot(const CurrentMapStore& store) {
  FLEETMAP_RETURN_IF_ERROR(WriteSnapshot(store, folder_ + "/" + kSnapshotName));
  // A crash here leaves journal records the snapshot already holds: restore skips them.
  FLEETMAP_RETURN_IF_ERROR(journal_.Reset());
  records_since_snapshot_ = 0;
  return core::OkStatus();
}

}  // namespace fleetmap::aggregator
