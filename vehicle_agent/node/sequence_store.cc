#include "vehicle_agent/node/sequence_store.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>

#include "core/io/file_io.h"
#include "core/io/number_text.h"

namespace fleetmap::vehicle_agent::node {
namespace {

namespace fs = std::filesystem;

// A positive int32 written in decimal, nothing else but an optional newline.
bool ParsePositive(const std::string& text, int32_t& out) {
  std::string digits = text;
  if (!digits.empty() && digits.back() == '\n') digits.pop_back();
  const core::Result<uint64_t> v = core::ParseCount(digits, "sequence", INT32_MAX);
  if (!v.ok() || *v < 1) return false;
  out = static_cast<int32_t>(*v);
  return true;
}

}  // namespace

int32_t SequenceStore::AfterPendingFiles() const {
  int32_t next = 1;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(state_dir_, ec)) {
    const std::string name = entry.path().filename().string();
    const std::string prefix = "tempmap_", suffix = ".fmtm";
    if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    int32_t sequence = 0;
    const std::string number =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (ParsePositive(number, sequence) && sequence < INT32_MAX)
      next = std::max(next, sequence + 1);
  }
  return next;
}

StoredSequence SequenceStore::Load() const {
  StoredSequence s;
  if (state_dir_.empty()) return s;
  s.next = AfterPendingFiles();
  core::Result<std::string> text = core::ReadFileBytes(path(), 64);
  if (!text.ok()) {
    // A first start has no file: that is not an issue.
    if (text.status().code() != core::StatusCode::kNotFound) s.issue = text.status();
    return s;
  }
  int32_t stored = 0;
  if (!ParsePositive(*text, stored)) {
    s.issue = core::DataLoss(path() + ": not a positive sequence number");
    return s;
  }
  s.next = std::max(s.next, stored);
  return s;
}

core::Status SequenceStore::Store(int32_t next) const {
  if (state_dir_.empty()) return core::OkStatus();
  std::error_code ec;
  fs::create_directories(state_dir_, ec);
  return core::WriteFileAtomically(path(), std::to_string(next) + "\n");
}

}  // namespace fleetmap::vehicle_agent::node
