// The messages of a fleet run's LCM logs (lcm-logger writes one per multicast group) as one
// stream, merged by the logger's receive stamps: what a single receiver on every group would
// have seen, in the order it saw it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::eval::recording {

struct LoggedEvent {
  int64_t wall_utime = 0;  // the logger's receive stamp (wall clock), microseconds
  int order = 0;           // keeps the logger's order among equal stamps
  std::string channel;
  std::vector<uint8_t> data;
};

// Every message of every log (any order), sorted by receive stamp; among equal stamps in the
// order the logs were given, then as each log holds them. InvalidArgument without a log or
// without a message; NotFound for a log that cannot be opened.
core::Result<std::vector<LoggedEvent>> ReadLogEvents(const std::vector<std::string>& log_paths);

}  // namespace fleetmap::eval::recording
