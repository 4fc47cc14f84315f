#include "aggregator/alignment/dominant_directions.h"

#include <cmath>

namespace fleetmap::aggregator {
namespace {

// Length within +- window of `angle`, and the length-weighted mean direction there.
std::pair<double, double> PeakAround(const std::vector<LineSegment>& lines, double angle,
                                     double window) {
  double length = 0.0, weighted = 0.0;
  for (const LineSegment& l : lines) {
    const double d = LineAngleDiff(angle, LineDirectionAngle(l.direction()));
    if (std::abs(d) > window) continue;
    length += l.length();
    weighted += l.length() * d;
  }
  const double mean = length > 0 ? angle + weighted / length : angle;
  return {length, LineDirectionAngle({std::cos(mean), std::sin(mean)})};
}

}  // namespace

core::Status DominantDirectionOptions::Validate() const {
  if (!(bin_rad > 0 && bin_rad <= M_PI / 36))
    return core::InvalidArgument("directions.bin_rad must be in (0, pi/36]");
  if (!(smoothing_rad >= 0)) return core::InvalidArgument("directions.smoothing_rad must be >= 0");
  if (!(min_separation_rad > 0 && min_separation_rad <= M_PI / 2))
    return core::InvalidArgument("directions.min_separation_rad must be in (0, pi/2]");
  return core::OkStatus();
}

Eigen::Vector2d DominantDirections::primary() const {
  return {std::cos(primary_rad), std::sin(primary_rad)};
}

Eigen::Vector2d DominantDirections::secondary() const {
  return {std::cos(secondary_rad), std::sin(secondary_rad)};
}

DominantDirections FindDominantDirections(const std::vector<LineSegment>& lines,
                                          const DominantDirectionOptions& o) {
  DominantDirections result;
  const int bins = static_cast<int>(std::round(M_PI / o.bin_rad));
  double best[2] = {0.0, 0.0};
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < bins; ++i) {
      const double angle = (i + 0.5) * M_PI / bins;
      if (pass == 1 && std::abs(LineAngleDiff(result.primary_rad, angle)) < o.min_separation_rad) {
        continue;
      }
      const auto [length, mean] = PeakAround(lines, angle, o.smoothing_rad + o.bin_rad / 2);
      if (length <= best[pass]) continue;
      best[pass] = length;
      (pass == 0 ? result.primary_rad : result.secondary_rad) = mean;
    }
  }
  result.primary_length = best[0];
  result.secondary_length = best[1];
  return result;
}

}  // namespace fleetmap::aggregator
