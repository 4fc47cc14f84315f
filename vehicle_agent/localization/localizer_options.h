// Every setting of the Monte Carlo localizer, with its default, unit and where it comes from.
// docs/localization.md lists them in the same order.
#pragma once

#include <cstdint>

#include "core/pose2.h"
#include "core/result.h"
#include "vehicle_agent/localization/beam_model.h"
#include "vehicle_agent/localization/global_search.h"
#include "vehicle_agent/localization/likelihood_field.h"
#include "vehicle_agent/localization/motion_model.h"
#include "vehicle_agent/localization/odometry_scale.h"
#include "vehicle_agent/localization/pose_hypotheses.h"
#include "vehicle_agent/localization/resampling.h"

namespace fleetmap::vehicle_agent {

// Which model computes W_avg (the paper's eq. 1) at the estimated pose.
enum class WAvgModel {
  kBeamModel,        // the paper's: sees removed obstacles as well as new ones
  kLikelihoodField,  // the particle filter's own model: cheaper, blind to removals
};

// What the localizer does with poses from a vehicle's own localization (AddExternalPose).
enum class ExternalPoseMode {
  kIgnore,       // MCL only; external poses are counted and dropped
  kPassThrough,  // report the external pose, carried forward by odometry; MCL sleeps
  kFuse,         // MCL, with the external pose as one more measurement (and re-initialise
                 // around it when the filter disagrees beyond external_reinit_mahalanobis)
};

enum class InitialPoseMode {
  kFromOptions,  // around initial_pose_in_map with the initial sigmas
  kGlobal,       // uniformly over the map's free cells (global localization)
};

struct LocalizerOptions {
  // --- measurement update (likelihood field, Probabilistic Robotics table 6.3) ---
  LikelihoodFieldOptions likelihood_field;
  // Beams scored per particle and update, >= 1; spread evenly over the usable returns. nav2
  // AMCL's max_beams (ROS 1: 30). 30 / 60 / 120 beams: 4.6 / 4.4 / 4.4 mm median error.
  int max_beams = 60;
  // --- prediction (sample_motion_model_odometry) ---
  MotionModelOptions motion;
  OdometryScaleOptions odometry_scale;  // each particle's own odometry scale
  // --- particle count (KLD sampling) and resampling ---
  KldOptions kld;
  // Resample (low variance) when N_eff < ratio * N, (0, 1]. 1 resamples at every update.
  double resample_min_neff_ratio = 0.5;
  // The filter updates once the vehicle has moved this far since the last update (AMCL:
  // update_min_d 0.2 m, update_min_a pi/6: 6.2 mm median error, these 4.4 mm). 0 updates at
  // every scan, standing still too, fitting the particles to one view. >= 0 each.
  double update_min_translation_m = 0.05;
  double update_min_rotation_rad = 0.05;
  // Motion longer than this between two filter updates (scans skipped while the agent fell
  // behind) is predicted in steps of at most about this size along the odometry's path, not
  // as one increment whose noise would spread the particles over metres (OdometryPath). Well
  // above the update thresholds: at every update the prediction is one increment. > 0 each.
  double prediction_step_m = 0.25;
  double prediction_step_rad = 0.25;
  // --- W_avg for the divergence detector ---
  WAvgModel w_avg_model = WAvgModel::kBeamModel;
  BeamModelOptions beam_model;  // used when w_avg_model is kBeamModel
  // --- initial pose (AMCL: initial_pose_*, initial_cov_xx = 0.25 m^2, initial_cov_aa =
  // (pi/12)^2) ---
  InitialPoseMode initial_pose_mode = InitialPoseMode::kFromOptions;
  core::Pose2 initial_pose_in_map;
  double initial_sigma_xy_m = 0.5;             // > 0
  double initial_sigma_theta_rad = M_PI / 12;  // > 0
  // kGlobal: the first scan is searched for over the whole map (global_search.h), the
  // distinct poses that fit it are followed scan by scan until one leads (pose_hypotheses.h),
  // and the particles start there, this far around it, m and rad (> 0 each); where nothing
  // fits, the particles spread over the whole free space.
  GlobalSearchOptions global_search;
  PoseHypothesesOptions hypotheses;
  double global_sigma_xy_m = 0.1;
  double global_sigma_theta_rad = 0.035;
  // --- lost (a kidnapped vehicle, a wrong start) ---
  // A scan is unexplained when fewer than lost_explained_share of its scored end points lie
  // within lost_explained_distance_m of a mapped obstacle at the estimate or ended short of
  // one in mapped free space (objects not in the map are the building's changes). Unexplained
  // for lost_after_s, the scan is searched for over the whole map, and when the best pose
  // found scores relocalize_margin more than the estimate (the search's score, [0, 1]) and
  // the scan tells places apart, the vehicle is lost: the poses found are followed, the
  // estimate among them with a head start (docs/localization.md, "Lost and kidnapped").
  // Otherwise the search is tried again after twice the wait, up to
  // lost_max_search_period_s. lost_after_s 0: never searched.
  double lost_explained_distance_m = 0.3;  // > 0
  double lost_explained_share = 0.8;       // [0, 1]
  double lost_after_s = 2.0;               // >= 0
  double lost_max_search_period_s = 30.0;  // >= lost_after_s
  double relocalize_margin = 0.15;         // [0, 1]
  // --- bad input ---
  // One odometry increment larger than this (between two consecutive samples) is a jump (a
  // reset of the odometry frame, a glitch): it is dropped, not applied. > 0.
  double max_odometry_step_m = 1.0;
  double max_odometry_step_rad = 1.0;
  // ... unless the time between the two samples explains it at up to this speed and yaw rate
  // (samples lost on the way; gaps up to 5 s), m/s and rad/s, >= 0 (0: fixed steps only).
  // Above any forklift's or AGV's 2-3 m/s, far below an odometry reset's step in 20 ms.
  double max_odometry_speed_mps = 4.0;
  double max_odometry_yaw_rate_radps = 3.0;
  // Odometry is carried forward (or back) to the scan's stamp with its v and omega, at most
  // this far, s, >= 0: a 50 Hz odometry sample is up to 20 ms off a scan, 1 cm at 0.5 m/s.
  double max_odometry_extrapolation_s = 0.1;
  // --- external poses ---
  ExternalPoseMode external_pose_mode = ExternalPoseMode::kIgnore;
  // Used when an external pose comes with a zero covariance. > 0.
  double external_sigma_xy_m = 0.05;
  double external_sigma_theta_rad = 0.02;
  // kFuse: re-initialise around the external pose when the filter's mean is further than this
  // many standard deviations (Mahalanobis, both covariances) from it. > 0.
  double external_reinit_mahalanobis = 6.0;
  // kPassThrough: without an external pose for this long, MCL takes over again from the last
  // one (carried forward by odometry). > 0.
  double external_timeout_s = 1.0;
  // --- determinism ---
  uint32_t seed = 1;  // the same seed and inputs give the same poses

  core::Status Validate() const;
};

}  // namespace fleetmap::vehicle_agent
