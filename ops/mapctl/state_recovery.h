// Recovery of a state folder the aggregator refuses to start on (a damaged journal or
// snapshot, aggregator/persistence/journal.h): the history that can still be read, i.e. the
// snapshot's merges, then the journal's intact records in order up to the first one that is not,
// and what that leaves out. Reads only; the caller writes the recovered history as the new state
// (state_writer.h), which keeps the damaged files in the backup folder.
#pragma once

#include <string>

#include "ops/mapctl/state_history.h"

namespace fleetmap::ops::mapctl {

struct Recovery {
  StateHistory history;            // what is recovered: versions 1..history.version()
  std::string snapshot_damage;     // empty: the snapshot (if any) was read whole
  std::string journal_damage;      // empty: the journal (if any) was read whole
  int journal_read = 0;            // intact journal records (the snapshot's included)
  int64_t journal_committed = -1;  // records the journal says it committed; -1: unknown
  // Versions after history.version() that were acknowledged but are gone: at least this
  // many (the journal's committed records that could not be read); -1: unknown.
  int64_t versions_lost = -1;

  bool damaged() const { return !snapshot_damage.empty() || !journal_damage.empty(); }
};

// NotFound when the folder holds neither snapshot nor journal.
core::Result<Recovery> ReadRecoverableHistory(const std::string& folder,
                                              int64_t max_file_bytes = int64_t{1} << 30);

}  // namespace fleetmap::ops::mapctl
