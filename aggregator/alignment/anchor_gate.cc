#include "aggregator/alignment/anchor_gate.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/pose_covariance.h"

namespace fleetmap::aggregator {
namespace {

template <typename... Values>
std::string Format(const char* format, Values... values) {
  char buf[200];
  std::snprintf(buf, sizeof(buf), format, values...);
  return buf;
}

}  // namespace

core::Status AnchorGateOptions::Validate() const {
  if (!(floor_sigma_xy_m >= 0) || !std::isfinite(floor_sigma_xy_m))
    return core::InvalidArgument("anchor_gate.floor_sigma_xy_m must be >= 0 and finite");
  if (!(floor_sigma_theta_rad >= 0) || !std::isfinite(floor_sigma_theta_rad))
    return core::InvalidArgument("anchor_gate.floor_sigma_theta_rad must be >= 0 and finite");
  if (!(max_mahalanobis_sq > 0))
    return core::InvalidArgument("anchor_gate.max_mahalanobis_sq must be > 0");
  if (!(min_explained_gain >= 0) || !std::isfinite(min_explained_gain))
    return core::InvalidArgument("anchor_gate.min_explained_gain must be >= 0 and finite");
  if (!(stand_max_sigma_xy_m >= 0) || !std::isfinite(stand_max_sigma_xy_m))
    return core::InvalidArgument("anchor_gate.stand_max_sigma_xy_m must be >= 0 and finite");
  if (!(stand_max_sigma_theta_rad >= 0) || !std::isfinite(stand_max_sigma_theta_rad))
    return core::InvalidArgument("anchor_gate.stand_max_sigma_theta_rad must be >= 0 and finite");
  return core::OkStatus();
}

AnchorGateVerdict JudgeCorrection(const core::Pose2& anchor,
                                  const std::optional<Eigen::Matrix3d>& covariance,
                                  const core::Pose2& correction, double explained_before,
                                  double explained_after, const AnchorGateOptions& options) {
  AnchorGateVerdict v;
  if (!covariance) return v;
  const core::Pose2 placed = correction * anchor;
  const Eigen::Vector3d move = core::PoseDifference(placed, anchor);
  const Eigen::Matrix3d floored =
      *covariance +
      core::DiagonalCovariance(options.floor_sigma_xy_m, options.floor_sigma_theta_rad);
  // Floored and symmetric positive semi-definite (checked on arrival): positive definite
  // unless both floors are 0, where a singular covariance keeps the anchor for any move.
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(floored);
  const bool singular = ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= 0;
  v.mahalanobis_sq = singular ? (move.isZero() ? 0.0 : INFINITY) : move.dot(ldlt.solve(move));
  const double gain = explained_after - explained_before;
  if (!options.enabled) return v;  // measured, not judged
  if (v.mahalanobis_sq > options.max_mahalanobis_sq) {
    v.take_correction = false;
    v.explanation = Format(
        "anchor stands: the correction's move (%.3f m) lies outside the "
        "anchor's covariance (squared Mahalanobis %.1f > %.1f)",
        move.head<2>().norm(), v.mahalanobis_sq, options.max_mahalanobis_sq);
  } else if (gain < options.min_explained_gain) {
    v.take_correction = false;
    v.explanation = Format(
        "anchor stands: the correction explains %.3f more of the map, %.3f "
        "needed",
        gain, options.min_explained_gain);
  }
  return v;
}

AnchorGateVerdict JudgeUnalignedAnchor(const std::optional<Eigen::Matrix3d>& covariance,
                                       const AnchorGateOptions& options) {
  AnchorGateVerdict v;
  v.take_correction = false;  // there is none
  if (!options.enabled || !covariance || options.stand_max_sigma_xy_m <= 0) return v;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> xy(covariance->topLeftCorner<2, 2>());
  const double sigma_xy_m = std::sqrt(std::max(0.0, xy.eigenvalues().maxCoeff()));
  const double sigma_theta_rad = std::sqrt(std::max(0.0, (*covariance)(2, 2)));
  if (!(sigma_xy_m <= options.stand_max_sigma_xy_m) ||
      !(sigma_theta_rad <= options.stand_max_sigma_theta_rad))
    return v;
  v.explanation = Format(
      "anchor stands: no correction found, the vehicle knew its anchor to "
      "%.3f m and %.2f deg",
      sigma_xy_m, sigma_theta_rad * 180 / M_PI);
  return v;
}

}  // namespace fleetmap::aggregator
