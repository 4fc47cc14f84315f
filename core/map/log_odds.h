// Log-odds arithmetic and the thresholds that turn a probability into a tri-state cell.
// Occupancy is stored as log-odds so that independent observations add (Thrun et al.,
// Probabilistic Robotics, ch. 9) and repeated evidence cannot overflow once clamped.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/result.h"

namespace fleetmap::core {

enum class CellState : uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

inline float ProbabilityToLogOdds(double p) { return static_cast<float>(std::log(p / (1.0 - p))); }
inline double LogOddsToProbability(float l) { return 1.0 / (1.0 + std::exp(-double{l})); }

// Same meaning as ROS map_server's occupied_thresh and free_thresh: a cell whose occupancy
// probability is above occupied_probability is occupied, below free_probability free, and
// unknown in between.
struct OccupancyThresholds {
  double occupied_probability = 0.65;  // (0, 1), above free_probability
  double free_probability = 0.196;     // (0, 1)
  Status Validate() const;
};

// Clamping bounds of stored log-odds, so that a cell seen occupied a thousand times can
// still be cleared by a few dozen free observations (a moved pallet).
struct LogOddsLimits {
  float min_log_odds = -4.6f;  // about p = 0.01
  float max_log_odds = 4.6f;   // about p = 0.99
  Status Validate() const;
};

}  // namespace fleetmap::core
