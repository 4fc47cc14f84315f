#include "ops/mapctl/state_writer.h"

#include <filesystem>

#include "aggregator/persistence/map_persistence.h"
#include "aggregator/persistence/snapshot.h"

namespace fleetmap::ops::mapctl {
namespace {

namespace fs = std::filesystem;

core::Status Backup(const fs::path& folder, const fs::path& backup) {
  std::error_code ec;
  fs::create_directories(backup, ec);
  if (ec) return core::IoError(backup.string() + ": cannot create: " + ec.message());
  const fs::path snapshot = folder / aggregator::MapPersistence::kSnapshotName;
  const fs::path journal = folder / aggregator::MapPersistence::kJournalName;
  if (fs::exists(snapshot, ec)) {
    fs::copy_file(snapshot, backup / snapshot.filename(), fs::copy_options::overwrite_existing, ec);
    if (ec) return core::IoError(snapshot.string() + ": cannot back up: " + ec.message());
  }
  if (fs::exists(journal, ec)) {
    fs::rename(journal, backup / journal.filename(), ec);
    if (ec) return core::IoError(journal.string() + ": cannot move to the backup: " + ec.message());
  }
  return core::OkStatus();
}

}  // namespace

core::Result<std::string> ReplaceState(const std::string& folder,
                                       const aggregator::CurrentMapStore& store,
                                       const std::string& backup_name) {
  const fs::path backup = fs::path(folder) / "backup" / backup_name;
  FLEETMAP_RETURN_IF_ERROR(Backup(folder, backup));
  FLEETMAP_RETURN_IF_ERROR(aggregator::WriteSnapshot(
      store, (fs::path(folder) / aggregator::MapPersistence::kSnapshotName).string()));
  return backup.string();
}

}  // namespace fleetmap::ops::mapctl
