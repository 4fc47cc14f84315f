#include "eval/summary_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fleetmap::eval {
namespace {

double Percentile(const std::vector<double>& sorted, double q) {
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * (pos - static_cast<double>(lo));
}

}  // namespace

SummaryStats Summarize(std::vector<double> values) {
  SummaryStats s;
  s.count = static_cast<int>(values.size());
  if (values.empty()) {
    s.median = s.p95 = s.max = s.mean = std::nan("");
    return s;
  }
  std::sort(values.begin(), values.end());
  s.median = Percentile(values, 0.5);
  s.p95 = Percentile(values, 0.95);
  s.max = values.back();
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(s.count);
  return s;
}

}  // namespace fleetmap::eval
