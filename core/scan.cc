#include "core/scan.h"

#include <cmath>
#include <string>

namespace fleetmap::core {

bool LaserScan::IsValidReturn(size_t i) const {
  const float r = ranges_m[i];
  return std::isfinite(r) && r >= range_min_m && r < range_max_m;
}

Status LaserScan::Validate() const {
  if (!std::isfinite(stamp_s)) return InvalidArgument("scan stamp is not finite");
  if (!std::isfinite(angle_min_rad) || !std::isfinite(angle_increment_rad) ||
      angle_increment_rad == 0.0) {
    return InvalidArgument("scan angles must be finite with a non-zero increment");
  }
  if (!std::isfinite(range_min_m) || !std::isfinite(range_max_m) || range_min_m < 0.0 ||
      range_max_m <= range_min_m) {
    return InvalidArgument("scan needs 0 <= range_min_m < range_max_m");
  }
  if (ranges_m.empty()) return InvalidArgument("scan has no beams");
  if (std::abs(angle_increment_rad) * static_cast<double>(ranges_m.size() - 1) >
      2.0 * M_PI + 1e-6) {
    return InvalidArgument("scan of " + std::to_string(ranges_m.size()) +
                           " beams spans more than 360 degrees");
  }
  if (!intensities.empty() && intensities.size() != ranges_m.size()) {
    return InvalidArgument("scan has " + std::to_string(intensities.size()) + " intensities for " +
                           std::to_string(ranges_m.size()) + " ranges");
  }
  return OkStatus();
}

}  // namespace fleetmap::core
