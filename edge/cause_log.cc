#include "edge/cause_log.h"

namespace fleetmap::edge {

void CauseLog::Info(const std::string& line) const {
  if (sink_) sink_(LogLevel::kInfo, line);
}

void CauseLog::Warning(const std::string& line) const {
  if (sink_) sink_(LogLevel::kWarning, line);
}

bool CauseLog::Once(const std::string& cause, const std::string& line) {
  if (seen_.count(cause) || seen_.size() >= kMaxCauses) return false;
  seen_.insert(cause);
  Warning(line + " (logged once; later ones are only counted, in STATUS)");
  return true;
}

}  // namespace fleetmap::edge
