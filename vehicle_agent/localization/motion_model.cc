#include "vehicle_agent/localization/motion_model.h"

#include <cmath>

#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {
namespace {

// The smaller of |a| and |pi - |a||: a reversing vehicle's rotation relative to its axis.
double AxisAngle(double a) { return std::min(std::abs(a), M_PI - std::abs(a)); }

// One standard normal draw scaled to the variance. The caller keeps one distribution per
// pose so that its pairs of draws (Marsaglia's polar method) are not thrown away.
double Sample(double variance, std::normal_distribution<double>& unit, std::mt19937& rng) {
  return variance > 0.0 ? std::sqrt(variance) * unit(rng) : 0.0;
}

// Into (-pi, pi]: a loop for the turn or two a motion increment adds (std::remainder costs
// more than the rest of the model), core::NormalizeAngle beyond.
double Wrap(double a) {
  if (std::abs(a) > 8.0 * M_PI) return core::NormalizeAngle(a);
  while (a > M_PI) a -= 2.0 * M_PI;
  while (a <= -M_PI) a += 2.0 * M_PI;
  return a;
}

}  // namespace

core::Status MotionModelOptions::Validate() const {
  const auto check = [](double v, const char* name) {
    return CheckOption(v >= 0 && std::isfinite(v), std::string("MotionModelOptions.") + name, v,
                       ">= 0 and finite");
  };
  FLEETMAP_RETURN_IF_ERROR(check(alpha1_rot_from_rot, "alpha1_rot_from_rot"));
  FLEETMAP_RETURN_IF_ERROR(check(alpha2_rot_from_trans, "alpha2_rot_from_trans"));
  FLEETMAP_RETURN_IF_ERROR(check(alpha3_trans_from_trans, "alpha3_trans_from_trans"));
  FLEETMAP_RETURN_IF_ERROR(check(alpha4_trans_from_rot, "alpha4_trans_from_rot"));
  FLEETMAP_RETURN_IF_ERROR(check(alpha5_lateral_from_trans, "alpha5_lateral_from_trans"));
  return check(min_translation_m, "min_translation_m");
}

core::Pose2 SampleMotionModelOdometry(const core::Pose2& pose, const core::Pose2& delta,
                                      const MotionModelOptions& o, std::mt19937& rng) {
  const double trans = std::hypot(delta.x_m, delta.y_m);
  const double rot1 = trans < o.min_translation_m ? 0.0 : std::atan2(delta.y_m, delta.x_m);
  const double rot2 = Wrap(delta.theta_rad - rot1);
  const double r1 = AxisAngle(rot1), r2 = AxisAngle(rot2), t2 = trans * trans;
  std::normal_distribution<double> unit(0.0, 1.0);
  const double rot1_hat =
      rot1 - Sample(o.alpha1_rot_from_rot * r1 * r1 + o.alpha2_rot_from_trans * t2, unit, rng);
  const double trans_hat =
      trans - Sample(o.alpha3_trans_from_trans * t2 + o.alpha4_trans_from_rot * (r1 * r1 + r2 * r2),
                     unit, rng);
  const double rot2_hat =
      rot2 - Sample(o.alpha1_rot_from_rot * r2 * r2 + o.alpha2_rot_from_trans * t2, unit, rng);
  const double lateral = Sample(o.alpha5_lateral_from_trans * t2, unit, rng);
  const double heading = pose.theta_rad + rot1_hat;
  const double c = std::cos(heading), s = std::sin(heading);
  return {pose.x_m + trans_hat * c - lateral * s, pose.y_m + trans_hat * s + lateral * c,
          Wrap(heading + rot2_hat)};
}

}  // namespace fleetmap::vehicle_agent
