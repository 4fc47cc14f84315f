// Log lines of the aggregator node. Bad input is logged once per cause, so a stream of
// broken messages neither floods the log nor goes unseen; the caller counts every one.
#pragma once

#include <set>
#include <string>

#include "aggregator/node/node_io.h"

namespace fleetmap::aggregator::node {

class CauseLog {
 public:
  explicit CauseLog(LogSink sink) : sink_(std::move(sink)) {}

  void Info(const std::string& line) const;
  void Warning(const std::string& line) const;
  // Logs `line` as a warning the first time `cause` (a short fixed key such as
  // "MAP_REQUEST: malformed") is seen; returns whether it did.
  bool Once(const std::string& cause, const std::string& line);

 private:
  // Causes are fixed keys, but a bound keeps a bug from growing the set without end.
  static constexpr size_t kMaxCauses = 256;
  LogSink sink_;
  std::set<std::string> seen_;
};

}  // namespace fleetmap::aggregator::node
