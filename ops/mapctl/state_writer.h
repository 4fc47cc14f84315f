// Replaces an aggregator state folder's map with another store's, keeping the old files.
// The caller holds the folder's lock (aggregator/persistence/state_dir_lock.h) so that no
// aggregator runs meanwhile. Order, so that a crash at any point leaves a folder the aggregator can
// open: the old snapshot is copied and the journal moved into the backup folder, then the
// new snapshot is written atomically (an empty journal is what a fresh snapshot has).
#pragma once

#include <string>

#include "aggregator/current_map_store.h"

namespace fleetmap::ops::mapctl {

// Writes `store` as `folder`'s new state after moving the old snapshot and journal to
// `<folder>/backup/<backup_name>/`. Returns that backup folder; IoError naming the file.
core::Result<std::string> ReplaceState(const std::string& folder,
                                       const aggregator::CurrentMapStore& store,
                                       const std::string& backup_name);

}  // namespace fleetmap::ops::mapctl
