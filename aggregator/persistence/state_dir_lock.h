// The aggregator's claim on its state folder: an exclusive flock(2) on `<folder>/lock`, held
// for as long as a MapPersistence lives. The kernel drops it when the process dies (also on
// SIGKILL), so a crash never leaves a stale lock behind. Tools that rewrite the folder
// (fleetmap-mapctl rollback, reset-region, promote) take the same lock and so refuse to run
// while an aggregator uses the folder: two writers would interleave journal records.
#pragma once

#include <string>

#include "core/result.h"

namespace fleetmap::aggregator {

class StateDirLock {
 public:
  static constexpr const char* kLockName = "lock";

  // Creates `<folder>/lock` if needed and locks it without waiting. FailedPrecondition when
  // another process (or another open lock in this one) holds it; IoError when the file
  // cannot be opened.
  static core::Result<StateDirLock> Acquire(const std::string& folder);

  StateDirLock() = default;  // holds nothing
  StateDirLock(StateDirLock&& other) noexcept;
  StateDirLock& operator=(StateDirLock&& other) noexcept;
  StateDirLock(const StateDirLock&) = delete;
  StateDirLock& operator=(const StateDirLock&) = delete;
  ~StateDirLock();

  bool held() const { return fd_ >= 0; }

 private:
  explicit StateDirLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace fleetmap::aggregator
