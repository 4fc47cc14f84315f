// Cells of the fleet map a vehicle's beams passed through, none ending there, and when: what
// a vehicle reports of the aggregator's candidates (vehicle_agent/candidate_watch.h) and what
// the aggregator drops them by (aggregator/candidates_seen_free.h).
#pragma once

#include <cstdint>
#include <vector>

namespace fleetmap::core {

struct SeenFreeCells {
  std::vector<int64_t> cells;  // cell indices of the fleet map, ascending
  double first_pass_s = 0.0;   // the first scan that passed through any of them
  double last_pass_s = 0.0;    // the last such scan
};

// Cells of the fleet map a vehicle's beams kept ending at: per cell, since when and until
// when, with no pause longer than the vehicle's hold_gap_s (vehicle_agent/candidate_watch.h).
struct HeldCells {
  std::vector<int64_t> cells;  // ascending
  std::vector<double> since_s, until_s;
};

}  // namespace fleetmap::core
