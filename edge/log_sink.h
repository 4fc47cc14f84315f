// Where a node's log lines go: the process prints them with its prefix, tests keep them.
#pragma once

#include <functional>
#include <string>

namespace fleetmap::edge {

enum class LogLevel { kInfo, kWarning };
using LogSink = std::function<void(LogLevel level, const std::string& line)>;

}  // namespace fleetmap::edge
