// A rigid 2D pose (x, y, theta) and the transforms built from it. Frames are named in
// variable names: `scan_in_map` is the scanner's pose expressed in the map frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace fleetmap::core {

// Wraps an angle into (-pi, pi].
double NormalizeAngle(double angle_rad);

struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;

  Pose2() = default;
  Pose2(double x, double y, double theta) : x_m(x), y_m(y), theta_rad(theta) {}

  static Pose2 FromIsometry(const Eigen::Isometry2d& t);
  Eigen::Isometry2d ToIsometry() const;
  Eigen::Vector2d translation() const { return {x_m, y_m}; }

  // this * other: `other` expressed in this pose's frame, mapped to the parent frame.
  Pose2 operator*(const Pose2& other) const;
  Pose2 Inverse() const;
  // Maps a point given in this pose's frame into the parent frame.
  Eigen::Vector2d Apply(const Eigen::Vector2d& point) const;
  // All three fields finite.
  bool IsFinite() const;
  std::string ToString() const;
};

// The pose `b` seen from `a`: a.Inverse() * b (the odometry increment from a to b).
Pose2 Between(const Pose2& a, const Pose2& b);

}  // namespace fleetmap::core
