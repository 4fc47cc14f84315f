// Median, 95th percentile and maximum of a sample, for the report's error figures.
#pragma once

#include <vector>

namespace fleetmap::eval {

struct SummaryStats {
  int count = 0;
  double median = 0.0;  // NaN when count is 0
  double p95 = 0.0;
  double max = 0.0;
  double mean = 0.0;
};

// Percentiles by linear interpolation between order statistics.
SummaryStats Summarize(std::vector<double> values);

}  // namespace fleetmap::eval
