// A node's log lines. Bad input is logged once per cause: a stream of broken messages neither
// floods the log nor goes unseen (the caller still counts every one, and STATUS says how many).
#pragma once

#include <set>
#include <string>

#include "edge/log_sink.h"

namespace fleetmap::edge {

class CauseLog {
 public:
  explicit CauseLog(LogSink sink) : sink_(std::move(sink)) {}

  void Info(const std::string& line) const;
  void Warning(const std::string& line) const;
  // Logs `line` as a warning the first time `cause` (a short fixed key such as
  // "MAP_DELTA: malformed") is seen; returns whether it did.
  bool Once(const std::string& cause, const std::string& line);

 private:
  // Causes are fixed keys, but a bound keeps a hostile sender from growing the set.
  static constexpr size_t kMaxCauses = 256;
  LogSink sink_;
  std::set<std::string> seen_;
};

}  // namespace fleetmap::edge
