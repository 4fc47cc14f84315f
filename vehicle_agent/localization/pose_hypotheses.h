// Global localization's second step: the poses a global search found, each followed on its
// own by odometry and fitted to every scan, their evidence summed over the scans, until one
// leads the rest clearly. A particle filter started around them all settles on whichever
// cloud happens to hold the best-placed particle after a scan or two, and in a hall of twin
// aisles that is the wrong aisle about a time in four (docs/localization.md); fitted poses
// compare the hypotheses at their best, and the sum lets the aisle's end, a column or a
// doorway decide once the vehicle reaches it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/map/occupancy_grid.h"
#include "core/pose2.h"
#include "core/result.h"
#include "vehicle_agent/localization/likelihood_field.h"

namespace fleetmap::vehicle_agent {

struct PoseHypothesesOptions {
  // Evidence is the mean log-likelihood per end point at the fitted pose, summed over scans.
  // The best hypothesis is taken when it leads every other by decide_margin after at least
  // min_scans scans; one further than drop_margin behind the best is dropped. > 0 each,
  // drop_margin >= decide_margin.
  double decide_margin = 4.0;
  double drop_margin = 12.0;
  // One scan costs a hypothesis at most this much against the scan's best (> 0): a person or
  // a vehicle right in front of the scanner, or a pallet the map lacks, leaves a scan that the
  // true pose explains worst of all, as a fitted wrong pose finds a wall for the near points;
  // only a disagreement that lasts over several scans decides.
  double max_loss_per_scan = 1.0;
  int min_scans = 3;  // >= 1
  // ... and after the vehicle drove this far (a radian turned counts as a metre: both show it
  // something new), m, >= 0: scans from one spot add the same evidence again and again.
  double min_travel_m = 1.0;
  // The fit: hill climbing on the likelihood field from the odometry's prediction, steps
  // halved from these down to fit_min_step_m (and the heading's in proportion). > 0 each.
  double fit_step_m = 0.05;
  double fit_step_rad = 0.02;
  double fit_min_step_m = 0.005;
  // ... against a prior around the odometry's prediction with these standard deviations
  // (m, rad; > 0 each): where the scan cannot tell (along an aisle), the odometry does.
  double fit_prior_sigma_m = 0.05;
  double fit_prior_sigma_rad = 0.025;
  // Two hypotheses that meet (closer than this, m and rad) are one, the better kept. >= 0.
  double same_m = 0.3;
  double same_rad = 0.1;
  // A search that returned as many poses as it may have left out others that fit the scan as
  // well (a vehicle between two long racks fits in every aisle): while no hypothesis leads,
  // the vehicle's scan is searched for again each time it drove this far, m (a radian turned
  // counts as a metre), and the poses found join the hypotheses. 0: never. >= 0.
  double research_travel_m = 2.0;
  // Evidence forgives the building's changes: an end point whose beam ended short of every
  // mapped obstacle in mapped free space, crossing none up to short_beam_margin_m before its
  // end (short_beam.h), scores as one short_beam_as_m from an obstacle. m, > 0 each.
  double short_beam_as_m = 0.3;
  double short_beam_margin_m = 0.3;
  // Hypotheses followed at most, the best kept, >= 1.
  int max_hypotheses = 64;
  core::Status Validate() const;
};

// One scan as the hypotheses weigh it.
struct HypothesisScan {
  const core::OccupancyGrid& map;
  const LikelihoodField& field;  // of `map`
  const std::vector<Eigen::Vector2f>& endpoints_in_base;
  core::Pose2 scanner_in_base;
};

struct PoseHypothesis {
  core::Pose2 base_in_map;
  double evidence = 0.0;  // summed mean log-likelihood per end point
};

class PoseHypotheses {
 public:
  explicit PoseHypotheses(const PoseHypothesesOptions& options) : options_(options) {}

  // Starts over from `seeds`, each fitted to the scan whose end points (vehicle frame) are
  // given; a seed's evidence is its head start (the pose the vehicle held gets one: the
  // others must beat it by driving, not by one scan that a change in the building explains
  // badly at the right place).
  void Start(const std::vector<PoseHypothesis>& seeds, const HypothesisScan& scan);
  // Adds `seeds` found after the start, each fitted to the current scan and entering
  // decide_margin behind the best: what it would have scored on earlier scans is unknown, and
  // level with the best, a twin of it took the lead at random about as often as not (seen on
  // the generated racked warehouse). It is taken only once it proves better.
  void Add(const std::vector<PoseHypothesis>& seeds, const HypothesisScan& scan);
  // Moves every hypothesis by the odometry's increment since the last scan and fits it.
  void Update(const core::Pose2& odometry_delta, const HypothesisScan& scan);
  void Clear() { hypotheses_.clear(); }

  bool active() const { return !hypotheses_.empty(); }
  // One is left, or the best leads the rest by decide_margin after min_scans scans.
  bool decided() const;
  // Driven since Start, m (a radian counts as a metre).
  double travel_m() const { return travel_m_; }
  const PoseHypothesis& best() const { return hypotheses_.front(); }      // active() only
  const std::vector<PoseHypothesis>& all() const { return hypotheses_; }  // best first
  // The spread of the hypotheses' positions and headings about the best, and at least
  // `floor` on the diagonal.
  Eigen::Matrix3d Covariance(const Eigen::Vector3d& floor) const;

 private:
  core::Pose2 Fit(const core::Pose2& start, const LikelihoodField& field,
                  const std::vector<Eigen::Vector2f>& endpoints) const;
  // Mean log-likelihood per end point at `base_in_map`, short beams forgiven.
  double Evidence(const core::Pose2& base_in_map, const HypothesisScan& scan) const;
  void Prune();

  PoseHypothesesOptions options_;
  std::vector<PoseHypothesis> hypotheses_;
  int scans_ = 0;
  double travel_m_ = 0.0;
};

}  // namespace fleetmap::vehicle_agent
