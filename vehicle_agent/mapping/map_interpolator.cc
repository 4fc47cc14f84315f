#include "vehicle_agent/mapping/map_interpolator.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::vehicle_agent {

namespace {

using Table = std::array<float, 1024>;

Table MakeTable(float min, float scale) {
  Table t;
  for (size_t i = 0; i < t.size(); ++i) {
    t[i] = static_cast<float>(core::LogOddsToProbability(min + i / scale));
  }
  return t;
}

}  // namespace

MapInterpolator::MapInterpolator(const core::OccupancyGrid* grid) : grid_(grid) {
  const core::LogOddsLimits& l = grid->limits();
  table_min_ = l.min_log_odds;
  table_scale_ = (Table().size() - 1) / (l.max_log_odds - l.min_log_odds);
  // The default limits' table is built once; other limits (rare) get their own, kept per
  // thread so that concurrent matchers never share a mutable cache.
  static const core::LogOddsLimits kDefault;
  static const Table kDefaultTable =
      MakeTable(kDefault.min_log_odds,
                (Table().size() - 1) / (kDefault.max_log_odds - kDefault.min_log_odds));
  if (l.min_log_odds == kDefault.min_log_odds && l.max_log_odds == kDefault.max_log_odds) {
    table_ = &kDefaultTable;
  } else {
    thread_local Table custom;
    custom = MakeTable(table_min_, table_scale_);
    table_ = &custom;
  }
}

}  // namespace fleetmap::vehicle_agent
