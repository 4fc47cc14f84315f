// A vehicle's motion along waypoints: turn in place towards the next waypoint, drive straight
// to it at constant speed, stand there for dwell_s, repeat; once through, or looping back to the
// first waypoint. The pose is a pure function of time, so every run of a scenario is exactly
// repeatable.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"

namespace fleetmap::sim {

struct RouteOptions {
  double speed_mps = 0.5;            // driving speed (the paper's 0.5 m/s)
  double angular_speed_radps = 0.5;  // turning speed at waypoints
  bool loop = false;                 // after the last waypoint, drive back to the first
  double start_s = 0.0;              // the vehicle stands at the first waypoint until then
  double dwell_s = 0.0;              // stands still this long on reaching each waypoint
};

struct RouteState {
  core::Pose2 pose;          // vehicle base in the map frame
  double v_mps = 0.0;        // forward speed
  double omega_radps = 0.0;  // turning rate
};

class Route {
 public:
  // Needs at least two waypoints, each leg longer than zero (checked by the scenario loader).
  Route(std::vector<Eigen::Vector2d> waypoints, RouteOptions options);

  RouteState StateAt(double t_s) const;
  // Time for one pass (once: to the last waypoint; loop: back to the first).
  double period_s() const { return phases_.empty() ? 0.0 : phases_.back().end_s; }
  const std::vector<Eigen::Vector2d>& waypoints() const { return waypoints_; }

 private:
  struct Phase {  // a turn in place or a straight drive
    double start_s, end_s;
    core::Pose2 from;
    double v_mps, omega_radps;
  };
  std::vector<Eigen::Vector2d> waypoints_;
  RouteOptions options_;
  std::vector<Phase> phases_;
};

}  // namespace fleetmap::sim
