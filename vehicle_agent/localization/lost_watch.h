// Telling when the vehicle is lost (LocalizerOptions, "lost"): a scan is explained when enough
// of its end points lie near a mapped obstacle at the estimate, or ended short of one in space
// the map holds free. Scans unexplained for lost_after_s make a search of the whole map due;
// a search that finds nothing clearly better makes the next one wait twice as long, up to
// lost_max_search_period_s. The localizer runs the search and says what it found.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/pose2.h"
#include "vehicle_agent/localization/likelihood_field.h"

namespace fleetmap::vehicle_agent {

// The share of `endpoints` (scan end points in the base frame) explained at `base_in_map`:
// within explained_distance_m of a mapped obstacle, or ending short in free space
// (short_beam.h). `field` is the likelihood field of `map`. NaN without end points.
double ExplainedShare(const core::OccupancyGrid& map, const LikelihoodField& field,
                      const std::vector<Eigen::Vector2f>& endpoints, const core::Pose2& base_in_map,
                      const core::Pose2& scanner_in_base, double explained_distance_m);

class LostWatch {
 public:
  // after_s 0: never lost. explained_share in [0, 1]; max_search_period_s >= after_s.
  LostWatch(double after_s, double explained_share, double max_search_period_s)
      : after_s_(after_s),
        explained_share_(explained_share),
        max_search_period_s_(max_search_period_s) {}

  // The explained share of a filter update at `now_s` (NaN: nothing to judge). An explained
  // scan ends being lost. Returns whether a search of the whole map is due now.
  bool SearchDue(double explained_share, double now_s);
  // The search found nothing clearly better than the estimate: wait longer for the next.
  void NothingBetter(double now_s);
  // The search found the vehicle elsewhere: lost until a scan is explained again.
  void FoundElsewhere() { lost_ = true; }
  // The particles restarted: scans are judged from here on.
  void Restart() { unexplained_since_s_ = std::numeric_limits<double>::quiet_NaN(); }

  bool lost() const { return lost_; }

 private:
  const double after_s_;
  const double explained_share_;
  const double max_search_period_s_;
  bool lost_ = false;
  double unexplained_since_s_ = std::numeric_limits<double>::quiet_NaN();  // NaN: explained
  double next_search_s_ = 0.0;
  double search_period_s_ = 0.0;
};

}  // namespace fleetmap::vehicle_agent
