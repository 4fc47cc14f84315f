#include "eval/recording/lcm_log_events.h"

#include <algorithm>
#include <lcm/lcm-cpp.hpp>
#include <utility>

namespace fleetmap::eval::recording {
namespace {

core::Status ReadLog(const std::string& path, std::vector<LoggedEvent>& events) {
  lcm::LogFile log(path, "r");
  if (!log.good()) return core::NotFound("cannot open LCM log " + path);
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    LoggedEvent ev;
    ev.wall_utime = e->timestamp;
    ev.order = static_cast<int>(events.size());
    ev.channel = e->channel;
    const auto* bytes = static_cast<const uint8_t*>(e->data);
    ev.data.assign(bytes, bytes + e->datalen);
    events.push_back(std::move(ev));
  }
  return core::OkStatus();
}

}  // namespace

core::Result<std::vector<LoggedEvent>> ReadLogEvents(const std::vector<std::string>& log_paths) {
  if (log_paths.empty()) return core::InvalidArgument("no LCM log to read");
  std::vector<LoggedEvent> events;
  for (const std::string& path : log_paths) FLEETMAP_RETURN_IF_ERROR(ReadLog(path, events));
  if (events.empty()) return core::InvalidArgument("the LCM logs hold no message");
  std::stable_sort(events.begin(), events.end(), [](const LoggedEvent& a, const LoggedEvent& b) {
    return a.wall_utime != b.wall_utime ? a.wall_utime < b.wall_utime : a.order < b.order;
  });
  return events;
}

}  // namespace fleetmap::eval::recording
