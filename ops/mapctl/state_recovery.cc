#include "ops/mapctl/state_recovery.h"

#include <algorithm>

#include "aggregator/persistence/journal.h"
#include "aggregator/persistence/snapshot.h"

namespace fleetmap::ops::mapctl {
namespace {

// The snapshot's merges, or none when it is damaged: the journal's records follow the
// snapshot's version, so without it they do not apply either.
void RecoverSnapshot(const std::string& path, int64_t max_bytes, Recovery& r) {
  auto snapshot = aggregator::ReadSnapshot(path, max_bytes);
  if (snapshot.status().code() == core::StatusCode::kNotFound) return;
  if (!snapshot.ok()) {
    r.snapshot_damage = snapshot.status().message();
    return;
  }
  StateHistory& h = r.history;
  h.snapshot_found = true;
  h.snapshot_version = snapshot->version;
  h.static_fingerprint = snapshot->static_fingerprint;
  h.commits = std::move(snapshot->commits);
  if (h.version() != h.snapshot_version) {
    r.snapshot_damage = path + ": holds commits up to version " + std::to_string(h.version()) +
                        " but says version " + std::to_string(h.snapshot_version);
    h = StateHistory{};
  }
}

// The journal's intact records that continue the history, in order.
core::Status RecoverJournal(const std::string& path, int64_t max_bytes, Recovery& r) {
  auto salvage = aggregator::SalvageJournal(path, max_bytes);
  if (salvage.status().code() == core::StatusCode::kNotFound) return core::OkStatus();
  if (!salvage.ok()) return salvage.status();
  r.journal_committed = salvage->committed_records;
  if (!salvage->damage.empty()) r.journal_damage = path + ": " + salvage->damage;
  StateHistory& h = r.history;
  for (size_t i = 0; i < salvage->records.size(); ++i) {
    const auto& bytes = salvage->records[i];
    auto commit = aggregator::DecodeCommit(bytes.data(), bytes.size());
    const std::string where = path + ": record " + std::to_string(i + 1);
    if (!commit.ok()) {
      r.journal_damage = where + ": " + commit.status().message();
      break;
    }
    if (commit->version <= h.version()) {  // the snapshot holds it already
      ++r.journal_read;
      continue;
    }
    if (commit->version != h.version() + 1) {
      r.journal_damage = where + ": version " + std::to_string(commit->version) +
                         " does not follow version " + std::to_string(h.version());
      break;
    }
    h.commits.push_back(std::move(commit).value());
    ++h.journal_records;
    ++r.journal_read;
  }
  return core::OkStatus();
}

}  // namespace

core::Result<Recovery> ReadRecoverableHistory(const std::string& folder, int64_t max_file_bytes) {
  StateFiles files;
  FLEETMAP_ASSIGN_OR_RETURN(files, FindStateFiles(folder));
  Recovery r;
  RecoverSnapshot(files.snapshot, max_file_bytes, r);
  FLEETMAP_RETURN_IF_ERROR(RecoverJournal(files.journal, max_file_bytes, r));
  if (r.journal_committed >= 0 && r.snapshot_damage.empty())
    r.versions_lost = std::max<int64_t>(0, r.journal_committed - r.journal_read);
  return r;
}

}  // namespace fleetmap::ops::mapctl
