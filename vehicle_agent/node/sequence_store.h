// The next temporary-map sequence number, kept in the state folder, so that numbering goes
// on across agent restarts: the aggregator answers a sequence it has handled with DUPLICATE,
// and a restarted agent that began again at 1 would have its new maps ignored.
#pragma once

#include <cstdint>
#include <string>

#include "core/result.h"

namespace fleetmap::vehicle_agent::node {

struct StoredSequence {
  int32_t next = 1;    // the sequence number the next temporary map gets, >= 1
  core::Status issue;  // why the stored number could not be read (then `next` is a guess)
};

class SequenceStore {
 public:
  // `state_dir` empty: nothing is stored and numbering starts at 1 on every start.
  explicit SequenceStore(std::string state_dir) : state_dir_(std::move(state_dir)) {}

  // The stored number, but never at or below a temporary map still waiting in the folder
  // (tempmap_<sequence>.fmtm, the outbox's files): a lost or corrupt counter file must not
  // make a new map reuse the number of a pending one.
  StoredSequence Load() const;
  // Stores `next` atomically (before the map numbered next - 1 is sent).
  core::Status Store(int32_t next) const;

  std::string path() const { return state_dir_ + "/next_tempmap_sequence"; }

 private:
  int32_t AfterPendingFiles() const;
  std::string state_dir_;
};

}  // namespace fleetmap::vehicle_agent::node
