#include "vehicle_agent/localization/localizer_options.h"

#include <cmath>

#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {
namespace {

core::Status CheckPositive(double v, const char* name) {
  return CheckOption(v > 0 && std::isfinite(v), std::string("LocalizerOptions.") + name, v,
                     "> 0 and finite");
}

core::Status CheckNonNegative(double v, const char* name) {
  return CheckOption(v >= 0 && std::isfinite(v), std::string("LocalizerOptions.") + name, v,
                     ">= 0 and finite");
}

core::Status CheckFinite(double v, const char* name) {
  return CheckOption(std::isfinite(v), std::string("LocalizerOptions.") + name, v, "finite");
}

}  // namespace

core::Status LocalizerOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(likelihood_field.Validate());
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(max_beams >= 1, "LocalizerOptions.max_beams", max_beams, ">= 1"));
  FLEETMAP_RETURN_IF_ERROR(motion.Validate());
  FLEETMAP_RETURN_IF_ERROR(odometry_scale.Validate());
  FLEETMAP_RETURN_IF_ERROR(kld.Validate());
  FLEETMAP_RETURN_IF_ERROR(CheckOption(resample_min_neff_ratio > 0 && resample_min_neff_ratio <= 1,
                                       "LocalizerOptions.resample_min_neff_ratio",
                                       resample_min_neff_ratio, "in (0, 1]"));
  FLEETMAP_RETURN_IF_ERROR(CheckNonNegative(update_min_translation_m, "update_min_translation_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckNonNegative(update_min_rotation_rad, "update_min_rotation_rad"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(prediction_step_m, "prediction_step_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(prediction_step_rad, "prediction_step_rad"));
  if (w_avg_model == WAvgModel::kBeamModel) FLEETMAP_RETURN_IF_ERROR(beam_model.Validate());
  const core::Pose2& p = initial_pose_in_map;
  FLEETMAP_RETURN_IF_ERROR(CheckFinite(p.x_m, "initial_pose_in_map.x_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckFinite(p.y_m, "initial_pose_in_map.y_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckFinite(p.theta_rad, "initial_pose_in_map.theta_rad"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(initial_sigma_xy_m, "initial_sigma_xy_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(initial_sigma_theta_rad, "initial_sigma_theta_rad"));
  FLEETMAP_RETURN_IF_ERROR(global_search.Validate());
  FLEETMAP_RETURN_IF_ERROR(hypotheses.Validate());
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(global_sigma_xy_m, "global_sigma_xy_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(global_sigma_theta_rad, "global_sigma_theta_rad"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(lost_explained_distance_m, "lost_explained_distance_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(lost_explained_share >= 0 && lost_explained_share <= 1,
                                       "LocalizerOptions.lost_explained_share",
                                       lost_explained_share, "in [0, 1]"));
  FLEETMAP_RETURN_IF_ERROR(CheckNonNegative(lost_after_s, "lost_after_s"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(
      lost_max_search_period_s >= lost_after_s && std::isfinite(lost_max_search_period_s),
      "LocalizerOptions.lost_max_search_period_s", lost_max_search_period_s, ">= lost_after_s"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(relocalize_margin >= 0 && relocalize_margin <= 1,
                                       "LocalizerOptions.relocalize_margin", relocalize_margin,
                                       "in [0, 1]"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(max_odometry_step_m, "max_odometry_step_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(max_odometry_step_rad, "max_odometry_step_rad"));
  FLEETMAP_RETURN_IF_ERROR(CheckNonNegative(max_odometry_speed_mps, "max_odometry_speed_mps"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckNonNegative(max_odometry_yaw_rate_radps, "max_odometry_yaw_rate_radps"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckNonNegative(max_odometry_extrapolation_s, "max_odometry_extrapolation_s"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(external_sigma_xy_m, "external_sigma_xy_m"));
  FLEETMAP_RETURN_IF_ERROR(CheckPositive(external_sigma_theta_rad, "external_sigma_theta_rad"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckPositive(external_reinit_mahalanobis, "external_reinit_mahalanobis"));
  return CheckPositive(external_timeout_s, "external_timeout_s");
}

}  // namespace fleetmap::vehicle_agent
