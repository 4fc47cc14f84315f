// Checks of a benchmark's reference relations themselves, so that a score against them is read
// for what it is. Measured on the SLAM benchmark logs in docs/localization.md:
// - Lattice: a relation's reference minus the log's odometry over the same two scans. aces'
//   relations are the odometry corrected in whole steps of 5 cm (and 0.25 deg): the grid of
//   the correlative search that made them. Rounded to 5 cm, a reference is up to 2.5 cm off on
//   each axis even where the search picked the right step, 1.9 cm on average for the exact
//   motion if the rounding is uniform.
// - Scan fit: how well a relation's two scans overlap when the second is placed by the
//   reference, and when placed by an estimate. Scans are the only witness of the motion; an
//   estimate that overlaps them better than the reference does is not wrong where it
//   disagrees with it.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "eval/carmen/carmen_log.h"
#include "eval/carmen/relations.h"

namespace fleetmap::eval::carmen {

struct LatticeCheck {
  int relations = 0;          // scored: within the span, both ends in the odometry
  int equal_to_odometry = 0;  // reference translation within the tolerance of the odometry's
  int on_lattice = 0;         // of the others: |reference - odometry| is a lattice vector's length
};

// The lattice vectors are step * (i, j) for whole i, j (up to 20 steps each way); only their
// lengths are compared, so the lattice's orientation does not matter. For a continuous
// difference the share `on_lattice` is what chance gives (fr079: 15% at 5 cm and 2 mm).
LatticeCheck CheckLattice(const std::vector<Relation>& relations,
                          const std::vector<TimedPose>& odometry, double step_m, double tolerance_m,
                          double max_span_s = std::numeric_limits<double>::infinity());

struct ScanFitOptions {
  double gate_m = 0.2;       // an end point farther than this from the other scan counts this
  double min_range_m = 0.1;  // returns used
  double max_range_m = 20.0;
};

// A laser record's returns as end points in the vehicle base frame.
std::vector<Eigen::Vector2d> EndPointsInBase(const LaserRecord& record,
                                             const ScanFitOptions& options);

// Mean distance of `second`'s points, placed in `first`'s frame by `second_in_first`, to the
// nearest of `first`'s points, each capped at `gate_m`. `gate_m` when `second` is empty.
double ScanFit(const std::vector<Eigen::Vector2d>& first,
               const std::vector<Eigen::Vector2d>& second, const core::Pose2& second_in_first,
               double gate_m);

struct FitComparison {
  int relations = 0;              // scored: both scans and both estimated poses found
  int estimate_better = 0;        // the estimate's fit is smaller by more than 0.1 mm
  int reference_better = 0;       // ... the reference's
  double reference_fit_m = 0.0;   // mean ScanFit with the reference's relative pose
  double estimate_fit_m = 0.0;    // ... with the estimate's
  double estimate_error_m = 0.0;  // mean translational error of the estimate (the benchmark's)
};

// Over the relations spanning at most `max_span_s`; scans and poses are found by time stamp
// as ScoreRelations finds them (nearest, within 1 ms). `log.lasers` and `estimate` sorted by time.
FitComparison CompareScanFit(const std::vector<Relation>& relations, const CarmenLog& log,
                             const std::vector<TimedPose>& estimate, const ScanFitOptions& options,
                             double max_span_s = std::numeric_limits<double>::infinity());

}  // namespace fleetmap::eval::carmen
