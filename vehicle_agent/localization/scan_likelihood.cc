#include "vehicle_agent/localization/scan_likelihood.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::vehicle_agent {

BeamReading ClassifyBeam(const core::LaserScan& scan, size_t i, double max_range_m) {
  const float r = scan.ranges_m[i];
  if (std::isnan(r) || r <= 0.0f || r < scan.range_min_m) return BeamReading::kInvalid;
  if (r >= std::min(scan.range_max_m, max_range_m)) return BeamReading::kNoReturn;  // incl. +inf
  return BeamReading::kReturn;
}

void ScanScoreAccumulator::AddBeam(double probability) {
  // NaN compares false: it lands on the floor like any impossible beam.
  score_.log_likelihood +=
      std::log(probability > kMinBeamLikelihood ? probability : kMinBeamLikelihood);
  ++score_.beams_used;
}

void ScanScoreAccumulator::AddLogBeam(double log_probability) {
  static const double kMinLog = std::log(kMinBeamLikelihood);
  score_.log_likelihood += log_probability > kMinLog ? log_probability : kMinLog;
  ++score_.beams_used;
}

ScanScore ScanScoreAccumulator::Finish() const {
  ScanScore s = score_;
  if (s.beams_used > 0) s.mean_beam_likelihood = std::exp(s.log_likelihood / s.beams_used);
  return s;
}

}  // namespace fleetmap::vehicle_agent
