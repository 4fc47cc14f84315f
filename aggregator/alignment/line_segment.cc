#include "aggregator/alignment/line_segment.h"

#include <cmath>

namespace fleetmap::aggregator {

Eigen::Vector2d LineSegment::direction() const {
  const Eigen::Vector2d d = b - a;
  const double n = d.norm();
  return n > 0 ? Eigen::Vector2d(d / n) : Eigen::Vector2d(1.0, 0.0);
}

Eigen::Vector2d LineSegment::normal() const {
  const double theta = hesse().theta_rad;
  return {std::cos(theta), std::sin(theta)};
}

HesseLine LineSegment::hesse() const {
  const Eigen::Vector2d d = direction();
  double theta = std::atan2(d.y(), d.x()) + M_PI / 2;  // the normal is the direction turned left
  theta = std::fmod(theta, M_PI);
  if (theta < 0) theta += M_PI;
  if (theta >= M_PI) theta -= M_PI;
  const Eigen::Vector2d n(std::cos(theta), std::sin(theta));
  return {n.dot(a), theta};
}

LineSegment LineSegment::Transformed(const core::Pose2& pose) const {
  return {pose.Apply(a), pose.Apply(b), oriented};
}

double LineDirectionAngle(const Eigen::Vector2d& direction) {
  double angle = std::fmod(std::atan2(direction.y(), direction.x()), M_PI);
  if (angle < 0) angle += M_PI;
  return angle >= M_PI ? angle - M_PI : angle;
}

double LineAngleDiff(double from_rad, double to_rad) {
  double d = std::fmod(to_rad - from_rad + M_PI / 2, M_PI);
  if (d < 0) d += M_PI;
  return d - M_PI / 2;
}

}  // namespace fleetmap::aggregator
