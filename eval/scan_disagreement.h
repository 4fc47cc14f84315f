// Where a scan, taken at a known pose, disagrees with the current map: returns in cells the
// map holds free and far from anything occupied (something appeared), and beams passing
// through semi-static obstacles of the map (something went). The truthmaps pipeline starts
// a temporary map when a run of neighbouring beams disagrees, as a perfect vehicle would;
// isolated beams (mixed pixels, dropouts) do not count.
#pragma once

#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/scan.h"

namespace fleetmap::eval {

struct DisagreementOptions {
  double max_range_m = 18.0;      // returns and beams beyond this are not judged
  int clearance_cells = 2;        // a return this close to an occupied cell agrees
  int pass_beam_step = 2;         // beams checked for passing through obstacles (every n-th)
  int pass_end_margin_cells = 3;  // cells before a return not judged (range noise)
  int min_run_beams = 4;          // neighbouring disagreeing beams that make a change
};

struct Disagreement {
  int disagreeing_beams = 0;
  int longest_run = 0;                                 // neighbouring disagreeing beams
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();  // of their end points, map frame
  bool changed(const DisagreementOptions& o) const { return longest_run >= o.min_run_beams; }
};

class ScanDisagreement {
 public:
  explicit ScanDisagreement(const DisagreementOptions& options) : options_(options) {}
  // Call with each new version of the map and its semi-static mask.
  void SetMap(const core::OccupancyGrid& map, const std::vector<uint8_t>& semi_static);
  Disagreement Judge(const core::LaserScan& scan, const core::Pose2& scanner_in_map) const;

 private:
  bool PassesObstacle(const Eigen::Vector2d& from, const Eigen::Vector2d& direction,
                      double length_m) const;

  DisagreementOptions options_;
  core::GridGeometry geometry_;
  std::vector<uint8_t> free_far_;  // free and no occupied cell within clearance
  std::vector<uint8_t> semi_static_;
  bool any_semi_static_ = false;
};

}  // namespace fleetmap::eval
