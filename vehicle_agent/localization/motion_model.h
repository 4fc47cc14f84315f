// The odometry motion model (Probabilistic Robotics, ch. 5.4, table 5.6,
// sample_motion_model_odometry): an odometry increment is split into a rotation, a straight
// translation and a second rotation, and each is perturbed with zero-mean Gaussian noise whose
// variance grows with the motion:
//   var(rot1)  = alpha1 rot1^2 + alpha2 trans^2
//   var(trans) = alpha3 trans^2 + alpha4 (rot1^2 + rot2^2)
//   var(rot2)  = alpha1 rot2^2 + alpha2 trans^2
// plus a sideways slip, var(lateral) = alpha5 trans^2, perpendicular to the travel heading.
// Driving backwards is not a half turn: rotations enter the noise as their smallest angle to
// the driving axis, so reversing 1 cm does not spread particles by pi (as in AMCL).
#pragma once

#include <random>

#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::vehicle_agent {

// The alphas are variance coefficients, as in the book and AMCL's odom_alpha1..4 (whose
// default 0.2, i.e. a 45% standard deviation, suits slipping wheels; our defaults describe
// an AGV's encoders with margin: about 3x the standard deviations the simulator applies, and
// a heading that turns by up to 0.06 rad per metre driven, as uncalibrated wheel diameters
// and the SLAM benchmark logs' odometry do, docs/localization.md).
struct MotionModelOptions {
  double alpha1_rot_from_rot = 0.004;      // rad^2 per rad^2 turned, >= 0 (sd 6% of a turn)
  double alpha2_rot_from_trans = 0.004;    // rad^2 per m^2 driven, >= 0 (sd 0.063 rad per m)
  double alpha3_trans_from_trans = 0.004;  // m^2 per m^2 driven, >= 0 (sd 6% of the distance)
  double alpha4_trans_from_rot = 0.0003;   // m^2 per rad^2 turned, >= 0 (sd 1.7 cm per rad)
  // Sideways slip, m^2 per m^2 driven, >= 0 (nav2's omni alpha5). Not in the book's model:
  // without it a particle cloud driving straight can only move sideways through heading
  // noise, and a cloud that settled a few cm to one side stays there for tens of metres
  // (measured in docs/localization.md).
  double alpha5_lateral_from_trans = 0.01;  // sd 10% of the distance
  // Below this translation the increment is a pure rotation (no heading of travel), m, >= 0.
  double min_translation_m = 1e-3;

  core::Status Validate() const;
};

// Draws the pose of one particle after the odometry increment `delta_in_base` (the vehicle's
// motion in its own previous frame, core::Between of two odometry poses).
core::Pose2 SampleMotionModelOdometry(const core::Pose2& pose, const core::Pose2& delta_in_base,
                                      const MotionModelOptions& options, std::mt19937& rng);

}  // namespace fleetmap::vehicle_agent
