// A simulated full disk and the bytes of damaged journals, for the persistence tests (their
// scratch folders: tests/support/scratch_folder.h).
#pragma once

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/scratch_folder.h"

namespace fleetmap::aggregator::testing {

// While alive, this process cannot write past `bytes` into any file (RLIMIT_FSIZE): writes
// fail with EFBIG as they would with ENOSPC on a full disk, after a partial write.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &old_);
    previous_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = old_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, previous_);
  }

 private:
  rlimit old_{};
  void (*previous_)(int) = SIG_DFL;
};

inline std::vector<char> ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void WriteAll(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
}

// What a crash leaves while the record after `before` was being written: the journal
// `after` (one record more) with `before`'s commit block, and its last `cut` bytes missing.
inline std::vector<char> CrashedWhileAppending(const std::vector<char>& before,
                                               std::vector<char> after, size_t cut) {
  std::copy(before.begin() + 8, before.begin() + 24, after.begin() + 8);  // the commit block
  after.resize(after.size() - cut);
  return after;
}

}  // namespace fleetmap::aggregator::testing
