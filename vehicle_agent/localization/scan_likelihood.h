// The measurement likelihood p(z | x, m) of one laser scan z, taken from pose x in map m: the
// paper's eq. (1), W_avg. Beams are combined in log space (a product of hundreds of densities
// underflows a double) and reported as the per-beam geometric mean
//   W_avg = exp((1 / n) * sum_i log p(z_i | x, m)),
// which does not depend on how many beams were used, so a subsampled scan, a scanner with
// more beams or a scan with some invalid returns all give comparable values.
#pragma once

#include <cstddef>
#include <limits>

#include "core/map/occupancy_grid.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace fleetmap::vehicle_agent {

// Probabilities below this are clamped before the log, so one impossible beam costs a large
// but finite penalty instead of -inf.
constexpr double kMinBeamLikelihood = 1e-12;

// What a model made of one scan.
struct ScanScore {
  // exp(mean log p) over the used beams; NaN when no beam was usable (no information: an
  // empty or malformed scan, no map yet). Callers skip NaN, never treat it as 0.
  double mean_beam_likelihood = std::numeric_limits<double>::quiet_NaN();
  double log_likelihood = 0.0;  // sum of log p over the used beams
  int beams_used = 0;
  int beams_invalid = 0;    // NaN, -inf, zero, negative or below range_min_m: skipped
  int beams_no_return = 0;  // +inf or at/above the range limit (the beam model uses them)
};

// A beam's reading as the models see it.
enum class BeamReading { kInvalid, kNoReturn, kReturn };

// Classifies beam `i`: NaN, -inf, r <= 0 and r < range_min_m are invalid; +inf and
// r >= min(range_max_m, max_range_m) are "no return"; the rest are returns.
BeamReading ClassifyBeam(const core::LaserScan& scan, size_t i, double max_range_m);

// A scan likelihood model. Not thread-safe for SetMap; Score is const and reentrant.
class ScanLikelihood {
 public:
  virtual ~ScanLikelihood() = default;

  // Replaces the map (a new current-map version). An empty grid means "no map": every
  // score is then NaN.
  virtual void SetMap(const core::OccupancyGrid& map) = 0;
  // A new version of the map in use that differs from it only inside `changed` (a merge's
  // tiles). Models that can update a part override this; the rest start afresh.
  virtual void UpdateMap(const core::OccupancyGrid& map, const core::CellWindow& changed) {
    (void)changed;
    SetMap(map);
  }

  // Scores `scan` (its own frame) seen from `scanner_in_map`. A scan that fails
  // LaserScan::Validate() or a non-finite pose scores NaN with beams_used = 0.
  virtual ScanScore Score(const core::LaserScan& scan, const core::Pose2& scanner_in_map) const = 0;

  // W_avg: the per-beam geometric mean of Score().
  double MeanBeamLikelihood(const core::LaserScan& scan, const core::Pose2& scanner_in_map) const {
    return Score(scan, scanner_in_map).mean_beam_likelihood;
  }
};

// Accumulates per-beam probabilities into a ScanScore (log space, clamped).
class ScanScoreAccumulator {
 public:
  void AddBeam(double probability);
  // The same with log p given (clamped at log kMinBeamLikelihood).
  void AddLogBeam(double log_probability);
  void CountInvalid() { ++score_.beams_invalid; }
  void CountNoReturn() { ++score_.beams_no_return; }
  ScanScore Finish() const;

 private:
  ScanScore score_;
};

}  // namespace fleetmap::vehicle_agent
