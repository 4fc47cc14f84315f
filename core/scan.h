// One 2D laser scan in the scanner's frame: beam i points at angle_min + i * increment.
// Ranges that are not finite or lie outside [range_min, range_max] are invalid returns.
#pragma once

#include <cstdint>
#include <vector>

#include "core/result.h"

namespace fleetmap::core {

struct LaserScan {
  double stamp_s = 0.0;              // acquisition time of the first beam, seconds
  double angle_min_rad = 0.0;        // angle of beam 0 in the scanner frame
  double angle_increment_rad = 0.0;  // signed step between beams
  double range_min_m = 0.0;          // returns below this are invalid
  double range_max_m = 0.0;          // returns at or above this are "no return"
  double scan_period_s = 0.0;        // time between two scans (0 if unknown)
  std::vector<float> ranges_m;       // one per beam
  std::vector<float> intensities;    // empty, or one per beam

  size_t size() const { return ranges_m.size(); }
  double angle(size_t i) const {
    return angle_min_rad + static_cast<double>(i) * angle_increment_rad;
  }
  // A usable return: finite and inside [range_min_m, range_max_m).
  bool IsValidReturn(size_t i) const;
  // Checks the header fields (finite, positive limits, matching intensity count). Individual
  // NaN ranges are allowed: they are invalid returns, not an invalid scan.
  Status Validate() const;
};

}  // namespace fleetmap::core
