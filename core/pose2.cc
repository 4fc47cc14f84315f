#include "core/pose2.h"

#include <cmath>
#include <cstdio>

namespace fleetmap::core {

double NormalizeAngle(double angle_rad) {
  double a = std::remainder(angle_rad, 2.0 * M_PI);  // in [-pi, pi]
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

Pose2 Pose2::FromIsometry(const Eigen::Isometry2d& t) {
  const Eigen::Rotation2Dd r(t.linear());
  return {t.translation().x(), t.translation().y(), NormalizeAngle(r.angle())};
}

Eigen::Isometry2d Pose2::ToIsometry() const {
  Eigen::Isometry2d t = Eigen::Isometry2d::Identity();
  t.translate(Eigen::Vector2d(x_m, y_m));
  t.rotate(theta_rad);
  return t;
}

Pose2 Pose2::operator*(const Pose2& other) const {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  return {x_m + c * other.x_m - s * other.y_m, y_m + s * other.x_m + c * other.y_m,
          NormalizeAngle(theta_rad + other.theta_rad)};
}

Pose2 Pose2::Inverse() const {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  return {-c * x_m - s * y_m, s * x_m - c * y_m, NormalizeAngle(-theta_rad)};
}

Eigen::Vector2d Pose2::Apply(const Eigen::Vector2d& p) const {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  return {x_m + c * p.x() - s * p.y(), y_m + s * p.x() + c * p.y()};
}

bool Pose2::IsFinite() const {
  return std::isfinite(x_m) && std::isfinite(y_m) && std::isfinite(theta_rad);
}

std::string Pose2::ToString() const {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.3f m, %.3f m, %.2f deg)", x_m, y_m, theta_rad * 180.0 / M_PI);
  return buf;
}

Pose2 Between(const Pose2& a, const Pose2& b) { return a.Inverse() * b; }

}  // namespace fleetmap::core
