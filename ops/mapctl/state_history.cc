#include "ops/mapctl/state_history.h"

#include <filesystem>

#include "aggregator/persistence/journal.h"
#include "aggregator/persistence/map_persistence.h"
#include "aggregator/persistence/snapshot.h"

namespace fleetmap::ops::mapctl {
namespace {

using aggregator::MapPersistence;

core::Status ReadSnapshotPart(const std::string& path, int64_t max_bytes, StateHistory& h) {
  auto snapshot = aggregator::ReadSnapshot(path, max_bytes);
  if (snapshot.status().code() == core::StatusCode::kNotFound) return core::OkStatus();
  if (!snapshot.ok()) return snapshot.status();  // it names the file
  h.snapshot_found = true;
  h.snapshot_version = snapshot->version;
  h.static_fingerprint = snapshot->static_fingerprint;
  h.commits = std::move(snapshot->commits);
  if (h.version() != h.snapshot_version) {
    return core::DataLoss(path + ": holds commits up to version " + std::to_string(h.version()) +
                          " but says version " + std::to_string(h.snapshot_version));
  }
  return core::OkStatus();
}

core::Status ReadJournalPart(const std::string& path, int64_t max_bytes, StateHistory& h) {
  auto journal = aggregator::ReadJournal(path, max_bytes);
  if (journal.status().code() == core::StatusCode::kNotFound) return core::OkStatus();
  if (!journal.ok()) return journal.status();  // it names the file
  h.torn_tail = journal->torn_tail;
  h.torn_detail = journal->torn_detail;
  for (size_t i = 0; i < journal->records.size(); ++i) {
    const auto& bytes = journal->records[i];
    const std::string where = path + " record " + std::to_string(i);
    auto commit = aggregator::DecodeCommit(bytes.data(), bytes.size());
    if (!commit.ok()) return commit.status().WithContext(where);
    // Records the snapshot already holds (a crash between snapshot and journal reset).
    if (commit->version <= h.version()) continue;
    if (commit->version != h.version() + 1) {
      return core::DataLoss(where + ": version " + std::to_string(commit->version) +
                            " does not follow version " + std::to_string(h.version()));
    }
    h.commits.push_back(std::move(commit).value());
    ++h.journal_records;
  }
  return core::OkStatus();
}

}  // namespace

core::Result<StateFiles> FindStateFiles(const std::string& folder) {
  StateFiles files{folder + "/" + MapPersistence::kSnapshotName,
                   folder + "/" + MapPersistence::kJournalName};
  std::error_code ec;
  if (!std::filesystem::exists(files.snapshot, ec) && !std::filesystem::exists(files.journal, ec)) {
    return core::NotFound(folder + ": no " + MapPersistence::kSnapshotName + " and no " +
                          MapPersistence::kJournalName + " (not an aggregator state folder?)");
  }
  return files;
}

core::Result<StateHistory> ReadStateHistory(const std::string& folder, int64_t max_file_bytes) {
  StateFiles files;
  FLEETMAP_ASSIGN_OR_RETURN(files, FindStateFiles(folder));
  StateHistory h;
  FLEETMAP_RETURN_IF_ERROR(ReadSnapshotPart(files.snapshot, max_file_bytes, h));
  FLEETMAP_RETURN_IF_ERROR(ReadJournalPart(files.journal, max_file_bytes, h));
  return h;
}

core::Result<aggregator::CurrentMapStore> RebuildStore(const core::OccupancyGrid& static_map,
                                                       const StateHistory& history,
                                                       uint64_t version,
                                                       const aggregator::StoreOptions& options) {
  if (history.snapshot_found &&
      history.static_fingerprint != aggregator::MapFingerprint(static_map)) {
    return core::FailedPrecondition(
        "the state folder was made for another static map (fingerprints differ): pass the "
        "aggregator's --map");
  }
  if (version > history.version()) {
    return core::OutOfRange("version " + std::to_string(version) +
                            " is past the history's last version " +
                            std::to_string(history.version()));
  }
  aggregator::CurrentMapStore store(static_map, options);
  for (const aggregator::MergeCommit& c : history.commits) {
    if (c.version > version) break;
    auto applied = store.Apply(c);
    if (!applied.ok()) return core::DataLoss(applied.status().message());
  }
  return store;
}

}  // namespace fleetmap::ops::mapctl
