// candump log files (`candump -l` / `candump -L`, read by canplayer), one frame per line:
//   (1649249898.730936) can0 243#00000000A0000400
// Standard ids have 3 hex digits, extended ids 8; an error frame's id carries 0x20000000;
// RTR is `123#R` (optionally `123#R4` with the length); CAN FD is `123##<flags><data>`;
// a classic 8-byte frame sent with DLC 9..15 ends in `_<dlc>`; data may contain '.'
// separators. Lines that do not start with '(' are ignored, as canplayer does.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"
#include "drivers/can/can_frame.h"

namespace fleetmap::drivers::can {

struct CandumpRecord {
  std::string interface;  // "can0"
  CanFrame frame;         // frame.stamp_s is the log time
};

core::Result<CandumpRecord> ParseCandumpLine(std::string_view line);
// The line for `record` (no newline); its time has microseconds like candump's.
std::string FormatCandumpLine(const CandumpRecord& record);

struct CandumpLogStats {
  size_t lines = 0;
  size_t records = 0;
  size_t ignored = 0;    // comments and empty lines
  size_t malformed = 0;  // lines starting with '(' that did not parse
};

struct CandumpLog {
  std::vector<CandumpRecord> records;
  CandumpLogStats stats;
  std::vector<std::string> errors;  // the first few malformed lines, with their line numbers
};

// Parses a whole log; malformed lines are counted and skipped, never fatal.
CandumpLog ParseCandumpLog(std::string_view text);
// Reads a file of at most `max_bytes`.
core::Result<CandumpLog> ReadCandumpLog(const std::string& path, int64_t max_bytes = 1 << 30);
// Writes every record, one line each, atomically (core::WriteFileAtomically).
core::Status WriteCandumpLog(const std::string& path, const std::vector<CandumpRecord>& records);

}  // namespace fleetmap::drivers::can
