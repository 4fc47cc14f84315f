// Reading a STATUS_<process> message's named counters (status_t: parallel name and value
// arrays, possibly of different lengths in a malformed message).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

#include "fleetmap/status_t.hpp"

namespace fleetmap::lcmtypes {

// The value of counter `name`; none when the message does not carry it.
inline std::optional<int64_t> StatusCounter(const fleetmap::status_t& status,
                                            const std::string& name) {
  const size_t n = std::min(status.counter_names.size(), status.counter_values.size());
  for (size_t i = 0; i < n; ++i)
    if (status.counter_names[i] == name) return status.counter_values[i];
  return std::nullopt;
}

}  // namespace fleetmap::lcmtypes
