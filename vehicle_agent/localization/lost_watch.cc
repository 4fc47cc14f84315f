#include "vehicle_agent/localization/lost_watch.h"

#include <algorithm>
#include <cmath>

#include "vehicle_agent/localization/short_beam.h"

namespace fleetmap::vehicle_agent {

// Only beams that went through a mapped obstacle, or ended far from any in unknown space,
// speak against the pose: one that ended short in free space met the building's change (a
// pallet, a person, a vehicle that is not in the map), which the true pose sees as well.
double ExplainedShare(const core::OccupancyGrid& map, const LikelihoodField& field,
                      const std::vector<Eigen::Vector2f>& endpoints, const core::Pose2& base_in_map,
                      const core::Pose2& scanner_in_base, double explained_distance_m) {
  if (endpoints.empty()) return std::numeric_limits<double>::quiet_NaN();
  const core::Pose2 scanner_in_map = base_in_map * scanner_in_base;
  const Eigen::Vector2d origin(scanner_in_map.x_m, scanner_in_map.y_m);
  int explained = 0;
  for (const Eigen::Vector2f& p : endpoints) {
    const Eigen::Vector2d end = base_in_map.Apply(p.cast<double>());
    explained += field.DistanceAt(end) <= explained_distance_m ||
                 EndsShortInFreeSpace(map, field, origin, end, explained_distance_m);
  }
  return static_cast<double>(explained) / endpoints.size();
}

bool LostWatch::SearchDue(double explained_share, double now_s) {
  if (after_s_ <= 0 || std::isnan(explained_share)) return false;
  if (explained_share >= explained_share_) {
    lost_ = false;
    unexplained_since_s_ = std::numeric_limits<double>::quiet_NaN();
    return false;
  }
  if (std::isnan(unexplained_since_s_)) {
    unexplained_since_s_ = now_s;
    search_period_s_ = after_s_;
    next_search_s_ = now_s + search_period_s_;
  }
  return !(now_s < next_search_s_);
}

// Less often while nothing better turns up: a vehicle that is where the estimate says, in a
// building that changed around it, would otherwise search every lost_after_s for ever.
void LostWatch::NothingBetter(double now_s) {
  search_period_s_ = std::min(2 * search_period_s_, max_search_period_s_);
  next_search_s_ = now_s + search_period_s_;
}

}  // namespace fleetmap::vehicle_agent
