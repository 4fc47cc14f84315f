// The messages of LCM log files (lcm-logger), in the order the logger received them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::ops::lan {

struct LogMessage {
  int64_t recv_utime = 0;  // the logger's receive stamp, microseconds since the Unix epoch
  std::string channel;
  std::vector<uint8_t> data;  // the LCM payload
};

// Reads every event of every log; several logs are merged by receive stamp (stable).
core::Result<std::vector<LogMessage>> ReadLogs(const std::vector<std::string>& paths);

}  // namespace fleetmap::ops::lan
