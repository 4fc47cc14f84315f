#include "vehicle_agent/localization/scan_endpoints.h"

#include <cmath>

#include "vehicle_agent/localization/scan_likelihood.h"

namespace fleetmap::vehicle_agent {

EndpointCounts ScanEndpoints(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                             int max_beams, double max_range_m,
                             std::vector<Eigen::Vector2f>& endpoints_in_base) {
  endpoints_in_base.clear();
  EndpointCounts counts;
  std::vector<size_t> usable;
  usable.reserve(scan.size());
  for (size_t i = 0; i < scan.size(); ++i) {
    switch (ClassifyBeam(scan, i, max_range_m)) {
      case BeamReading::kInvalid:
        ++counts.invalid;
        break;
      case BeamReading::kNoReturn:
        ++counts.no_return;
        break;
      case BeamReading::kReturn:
        usable.push_back(i);
        break;
    }
  }
  counts.returns = static_cast<int>(usable.size());
  const size_t n = std::min(usable.size(), static_cast<size_t>(std::max(max_beams, 0)));
  for (size_t k = 0; k < n; ++k) {
    // Evenly spread: the k-th of n picks among the usable returns.
    const size_t i = usable[k * usable.size() / n];
    const double a = scan.angle(i), r = scan.ranges_m[i];
    const Eigen::Vector2d p = scanner_in_base.Apply({r * std::cos(a), r * std::sin(a)});
    endpoints_in_base.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  }
  return counts;
}

}  // namespace fleetmap::vehicle_agent
