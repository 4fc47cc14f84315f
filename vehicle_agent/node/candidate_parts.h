// The aggregator's candidates arrive in parts (MAP_CANDIDATES, one datagram each): the set is
// used once every part of one sending is in. A part of a newer sending starts over; a lost
// part leaves the last whole set in use until the next sending (every keyframe period).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "core/result.h"
#include "fleetmap/map_candidates_t.hpp"

namespace fleetmap::vehicle_agent::node {

class CandidateParts {
 public:
  // The whole set when this part completes it; nothing while parts are missing.
  // InvalidArgument for a part that cannot be (its number, count or cells).
  core::Result<std::optional<std::vector<int64_t>>> Add(const fleetmap::map_candidates_t& part);

 private:
  int64_t utime_ = -1;
  int32_t version_ = -1;
  int16_t parts_ = 0;
  std::map<int16_t, std::vector<int64_t>> received_;
};

}  // namespace fleetmap::vehicle_agent::node
