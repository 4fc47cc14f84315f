#include "sim/route.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace fleetmap::sim {

Route::Route(std::vector<Eigen::Vector2d> waypoints, RouteOptions options)
    : waypoints_(std::move(waypoints)), options_(options) {
  assert(waypoints_.size() >= 2 && options_.speed_mps > 0 && options_.angular_speed_radps > 0);
  std::vector<Eigen::Vector2d> stops = waypoints_;
  if (options_.loop) stops.push_back(waypoints_.front());
  const Eigen::Vector2d first_leg = stops[1] - stops[0];
  core::Pose2 pose(stops[0].x(), stops[0].y(), std::atan2(first_leg.y(), first_leg.x()));
  double t = 0.0;
  for (size_t i = 0; i + 1 < stops.size(); ++i) {
    const Eigen::Vector2d leg = stops[i + 1] - stops[i];
    const double heading = std::atan2(leg.y(), leg.x());
    const double turn = core::NormalizeAngle(heading - pose.theta_rad);
    if (std::abs(turn) > 1e-9) {
      const double duration = std::abs(turn) / options_.angular_speed_radps;
      phases_.push_back(
          {t, t + duration, pose, 0.0, std::copysign(options_.angular_speed_radps, turn)});
      t += duration;
      pose.theta_rad = heading;
    }
    const double duration = leg.norm() / options_.speed_mps;
    phases_.push_back({t, t + duration, pose, options_.speed_mps, 0.0});
    t += duration;
    pose = core::Pose2(stops[i + 1].x(), stops[i + 1].y(), heading);
    if (options_.dwell_s > 0) {
      phases_.push_back({t, t + options_.dwell_s, pose, 0.0, 0.0});
      t += options_.dwell_s;
    }
  }
  // A looping route turns back to its starting heading to close the cycle.
  if (options_.loop) {
    const double turn = core::NormalizeAngle(phases_.front().from.theta_rad - pose.theta_rad);
    if (std::abs(turn) > 1e-9) {
      const double duration = std::abs(turn) / options_.angular_speed_radps;
      phases_.push_back(
          {t, t + duration, pose, 0.0, std::copysign(options_.angular_speed_radps, turn)});
    }
  }
}

RouteState Route::StateAt(double t_s) const {
  double t = t_s - options_.start_s;
  if (t <= 0.0) return {phases_.front().from, 0.0, 0.0};
  if (t >= period_s()) {
    if (!options_.loop) {
      const Phase& last = phases_.back();
      const double d = last.end_s - last.start_s;
      return {core::Pose2(last.from.x_m + std::cos(last.from.theta_rad) * last.v_mps * d,
                          last.from.y_m + std::sin(last.from.theta_rad) * last.v_mps * d,
                          core::NormalizeAngle(last.from.theta_rad + last.omega_radps * d)),
              0.0, 0.0};
    }
    t = std::fmod(t, period_s());
  }
  const auto it = std::upper_bound(phases_.begin(), phases_.end(), t,
                                   [](double v, const Phase& p) { return v < p.end_s; });
  const Phase& p = it == phases_.end() ? phases_.back() : *it;
  const double d = std::clamp(t - p.start_s, 0.0, p.end_s - p.start_s);
  const core::Pose2 pose(p.from.x_m + std::cos(p.from.theta_rad) * p.v_mps * d,
                         p.from.y_m + std::sin(p.from.theta_rad) * p.v_mps * d,
                         core::NormalizeAngle(p.from.theta_rad + p.omega_radps * d));
  return {pose, p.v_mps, p.omega_radps};
}

}  // namespace fleetmap::sim
