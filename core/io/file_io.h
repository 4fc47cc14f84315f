// Whole-file reads with a size limit, and atomic replacement of a file: how fleetmap writes
// maps, snapshots and reports so that a crash or a full disk never leaves half a file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/result.h"

namespace fleetmap::core {

// Reads a whole file of at most max_bytes into memory (NotFound, IoError, OutOfRange).
Result<std::string> ReadFileBytes(const std::string& path, int64_t max_bytes);

// How long a written file must last.
enum class Durability {
  kPowerLoss,     // fsync the file and its folder: it survives the machine losing power
  kProcessCrash,  // no fsync: it survives the process being killed, not a power loss. For
                  // a real-time loop: fsync can stall it for seconds on a busy or slow disk.
};

// Replaces `path` by `bytes` atomically: writes a temporary file in the same folder, fsyncs
// it, renames it over `path` and fsyncs the folder (kPowerLoss; kProcessCrash skips both
// fsyncs). On any failure (missing or unwritable folder, full disk) returns IoError naming the
// path and leaves neither a partial `path` nor the temporary file; an existing `path` is then
// untouched. New files get mode 0644.
Status WriteFileAtomically(const std::string& path, std::string_view bytes,
                           Durability durability = Durability::kPowerLoss);

}  // namespace fleetmap::core
