// Whether to move a temporary map away from where its vehicle placed it. The vehicle sends the
// covariance of its anchor (the particle set's, at the scan the map started at); a correction
// that moves the anchor further than that covariance allows is more likely a wrong match in a
// repetitive or line-poor place than a localization error, and a correction that does not make
// the static map explain more of the temporary map by a clear margin has nothing to show for
// the move. In both cases the anchor stands: the map is placed where the vehicle put it.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>

#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::aggregator {

struct AnchorGateOptions {
  // false: every accepted correction is taken (the move is still measured). Maps without a
  // covariance are never judged.
  bool enabled = true;
  // Added to the anchor's standard deviations (in quadrature) before the test: what the
  // vehicle's covariance leaves out (the temporary map's own drift from its anchor, the
  // filter's overconfidence, the static map's quantisation). m, rad, >= 0.
  double floor_sigma_xy_m = 0.05;
  double floor_sigma_theta_rad = 0.01;
  // The correction's squared Mahalanobis distance under the floored covariance, > 0:
  // chi-square of 3 degrees of freedom gives 11.34 at 99 % for an honest covariance.
  // Infinity (the default): not tested. The localizer's covariance is overconfident (the
  // anchors' NEES p95 has a median of 81 over the world suite, 7.81 if honest), and at any
  // limit from 3 to 100 the gate kept more wrong anchors than it refused wrong corrections
  // (docs/aggregator.md, "The anchor gate").
  double max_mahalanobis_sq = INFINITY;
  // The rise of the explained fraction (of the temporary surface cells near static ones) a
  // correction must bring to be taken, >= 0. At 0, a correction that makes the static map
  // explain less of the map than the anchor did (which ConfidenceOptions::max_overlap_loss
  // still accepts) is not taken: the world suite's alignment p95 median 1.66 -> 1.53 cells.
  double min_explained_gain = 0.0;
  // Where no correction is accepted (too few lines, an ambiguous shift, a worse fit), a map
  // whose vehicle knows its anchor this well is placed at the anchor rather than rejected:
  // the largest standard deviation of the anchor's position, m, and of its heading, rad,
  // >= 0 (0: such a map is rejected). On the world suite the rejected share fell from a
  // median / max of 0.030 / 0.266 to 0.009 / 0.149, changed-cell F1 even (docs/aggregator.md).
  double stand_max_sigma_xy_m = 0.03;
  double stand_max_sigma_theta_rad = 1.0 * M_PI / 180;
  core::Status Validate() const;
};

struct AnchorGateVerdict {
  bool take_correction = true;
  double mahalanobis_sq = NAN;  // of the correction's move of the anchor; NaN: no covariance
  std::string explanation;      // why the anchor stands (empty when the correction is taken)
};

// `correction` moves `anchor` (placed = correction * anchor, both in the static frame);
// `covariance` is the anchor's over (x_m, y_m, theta_rad), none when the vehicle sent none
// (then the correction is taken). The explained fractions are those with the anchor alone
// and with the correction.
AnchorGateVerdict JudgeCorrection(const core::Pose2& anchor,
                                  const std::optional<Eigen::Matrix3d>& covariance,
                                  const core::Pose2& correction, double explained_before,
                                  double explained_after, const AnchorGateOptions& options);

// Whether the anchor is known well enough to stand where no correction was found: its
// covariance's largest positional and its heading standard deviation within the options'
// (the floors are not added: they widen the test of a move, not the trust in the anchor).
// The explanation says so, with the figures.
AnchorGateVerdict JudgeUnalignedAnchor(const std::optional<Eigen::Matrix3d>& covariance,
                                       const AnchorGateOptions& options);

}  // namespace fleetmap::aggregator
