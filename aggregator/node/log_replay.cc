#include "aggregator/node/log_replay.h"

#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <memory>

#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {
namespace {

// One log with its next event copied out (LogFile reuses the event's memory).
struct Cursor {
  std::unique_ptr<lcm::LogFile> log;
  bool has_event = false;
  int64_t timestamp = 0;
  std::string channel;
  std::vector<uint8_t> data;

  void Next() {
    const lcm::LogEvent* ev = log->readNextEvent();
    has_event = ev != nullptr;
    if (!ev) return;
    timestamp = ev->timestamp;
    channel = ev->channel;
    const auto* bytes = static_cast<const uint8_t*>(ev->data);
    data.assign(bytes, bytes + (ev->datalen > 0 ? ev->datalen : 0));
  }
};

}  // namespace

bool IsUplinkChannel(const std::string& channel) {
  if (channel == lcmtypes::kMapRequestChannel) return true;
  if (lcmtypes::HasPrefix(channel, lcmtypes::kCandidatesFreePrefix)) return true;
  return lcmtypes::IsTempMapTileChannel(channel);
}

core::Result<ReplayStats> ReplayLogs(const std::vector<std::string>& paths, AggregatorNode& node,
                                     const volatile std::sig_atomic_t* stop) {
  std::vector<Cursor> cursors;
  for (const std::string& path : paths) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return core::NotFound(path + ": no such log");
    Cursor c;
    c.log = std::make_unique<lcm::LogFile>(path, "r");
    if (!c.log->good()) return core::IoError(path + ": cannot open the LCM log");
    c.Next();
    cursors.push_back(std::move(c));
  }
  ReplayStats stats;
  while (!(stop && *stop)) {
    Cursor* next = nullptr;
    for (Cursor& c : cursors)
      if (c.has_event && (!next || c.timestamp < next->timestamp)) next = &c;
    if (!next) break;
    ++stats.events;
    if (IsUplinkChannel(next->channel)) {
      const double t = lcmtypes::FromUtime(next->timestamp);
      if (stats.fed == 0) stats.first_s = t;
      stats.last_s = t;
      ++stats.fed;
      node.OnMessage(next->channel, next->data.data(), static_cast<int>(next->data.size()), t);
      node.Tick(t);
    } else {
      ++stats.skipped;
    }
    next->Next();
  }
  return stats;
}

}  // namespace fleetmap::aggregator::node
