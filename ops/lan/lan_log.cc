#include "ops/lan/lan_log.h"

#include <algorithm>
#include <lcm/lcm-cpp.hpp>

namespace fleetmap::ops::lan {

core::Result<std::vector<LogMessage>> ReadLogs(const std::vector<std::string>& paths) {
  std::vector<LogMessage> messages;
  for (const std::string& path : paths) {
    lcm::LogFile log(path, "r");
    if (!log.good()) return core::NotFound("cannot open LCM log " + path);
    while (const lcm::LogEvent* e = log.readNextEvent()) {
      LogMessage m;
      m.recv_utime = e->timestamp;
      m.channel = e->channel;
      const auto* bytes = static_cast<const uint8_t*>(e->data);
      m.data.assign(bytes, bytes + e->datalen);
      messages.push_back(std::move(m));
    }
  }
  std::stable_sort(messages.begin(), messages.end(), [](const LogMessage& a, const LogMessage& b) {
    return a.recv_utime < b.recv_utime;
  });
  return messages;
}

}  // namespace fleetmap::ops::lan
