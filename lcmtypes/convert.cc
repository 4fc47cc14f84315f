#include "lcmtypes/convert.h"

#include <cmath>

namespace fleetmap::lcmtypes {

fleetmap::pose2d_t ToMessage(const core::Pose2& p) {
  fleetmap::pose2d_t m;
  m.x_m = p.x_m;
  m.y_m = p.y_m;
  m.theta_rad = p.theta_rad;
  return m;
}

core::Pose2 FromMessage(const fleetmap::pose2d_t& m) { return {m.x_m, m.y_m, m.theta_rad}; }

core::Status CheckVehicleId(const std::string& id) {
  if (id.empty() || id.size() > 64)
    return core::InvalidArgument("vehicle_id must have 1 to 64 characters");
  for (const char c : id) {
    if (c < 0x21 || c > 0x7E) {
      return core::InvalidArgument("vehicle_id may only hold printable ASCII characters");
    }
  }
  return core::OkStatus();
}

int64_t ToUtime(double stamp_s) { return static_cast<int64_t>(std::llround(stamp_s * 1e6)); }
double FromUtime(int64_t utime) { return static_cast<double>(utime) * 1e-6; }

fleetmap::laser_scan_t ToMessage(const core::LaserScan& scan, const std::string& vehicle_id,
                                 int32_t seq) {
  fleetmap::laser_scan_t m;
  m.utime = ToUtime(scan.stamp_s);
  m.vehicle_id = vehicle_id;
  m.seq = seq;
  m.angle_min_rad = static_cast<float>(scan.angle_min_rad);
  m.angle_increment_rad = static_cast<float>(scan.angle_increment_rad);
  m.range_min_m = static_cast<float>(scan.range_min_m);
  m.range_max_m = static_cast<float>(scan.range_max_m);
  m.scan_period_s = static_cast<float>(scan.scan_period_s);
  m.ranges_m = scan.ranges_m;
  m.num_ranges = static_cast<int32_t>(m.ranges_m.size());  // LCM reads num_* when encoding
  m.intensities = scan.intensities;
  m.num_intensities = static_cast<int32_t>(m.intensities.size());
  return m;
}

core::Result<core::LaserScan> FromMessage(const fleetmap::laser_scan_t& m) {
  FLEETMAP_RETURN_IF_ERROR(CheckVehicleId(m.vehicle_id));
  if (m.num_ranges < 1 || m.num_ranges > kMaxBeams) {
    return core::OutOfRange("scan of " + std::to_string(m.num_ranges) + " beams (allowed 1 to " +
                            std::to_string(kMaxBeams) + ")");
  }
  core::LaserScan scan;
  scan.stamp_s = FromUtime(m.utime);
  scan.angle_min_rad = m.angle_min_rad;
  scan.angle_increment_rad = m.angle_increment_rad;
  scan.range_min_m = m.range_min_m;
  scan.range_max_m = m.range_max_m;
  scan.scan_period_s = m.scan_period_s;
  scan.ranges_m = m.ranges_m;
  scan.intensities = m.intensities;
  FLEETMAP_RETURN_IF_ERROR(scan.Validate().WithContext("scan from " + m.vehicle_id));
  return scan;
}

fleetmap::odometry_t ToMessage(const core::OdometrySample& o, const std::string& vehicle_id) {
  fleetmap::odometry_t m;
  m.utime = ToUtime(o.stamp_s);
  m.vehicle_id = vehicle_id;
  m.pose = ToMessage(o.pose_in_odom);
  m.v_mps = o.v_mps;
  m.omega_radps = o.omega_radps;
  return m;
}

core::Result<core::OdometrySample> FromMessage(const fleetmap::odometry_t& m) {
  FLEETMAP_RETURN_IF_ERROR(CheckVehicleId(m.vehicle_id));
  core::OdometrySample o{FromUtime(m.utime), FromMessage(m.pose), m.v_mps, m.omega_radps};
  FLEETMAP_RETURN_IF_ERROR(o.Validate().WithContext("odometry from " + m.vehicle_id));
  return o;
}

void ToRowMajor(const Eigen::Matrix3d& covariance, double (&out)[9]) {
  for (int i = 0; i < 9; ++i) out[i] = covariance(i / 3, i % 3);
}

Eigen::Matrix3d FromRowMajor(const double (&in)[9]) {
  Eigen::Matrix3d c;
  for (int i = 0; i < 9; ++i) c(i / 3, i % 3) = in[i];
  return c;
}

fleetmap::pose_with_covariance_t ToMessage(const core::PoseEstimate& p,
                                           const std::string& vehicle_id) {
  fleetmap::pose_with_covariance_t m;
  m.utime = ToUtime(p.stamp_s);
  m.vehicle_id = vehicle_id;
  m.pose = ToMessage(p.pose_in_map);
  ToRowMajor(p.covariance, m.covariance);
  m.map_version = p.map_version;
  return m;
}

core::Result<core::PoseEstimate> FromMessage(const fleetmap::pose_with_covariance_t& m) {
  FLEETMAP_RETURN_IF_ERROR(CheckVehicleId(m.vehicle_id));
  core::PoseEstimate p;
  p.stamp_s = FromUtime(m.utime);
  p.pose_in_map = FromMessage(m.pose);
  p.covariance = FromRowMajor(m.covariance);
  p.map_version = m.map_version;
  FLEETMAP_RETURN_IF_ERROR(p.Validate().WithContext("pose from " + m.vehicle_id));
  return p;
}

}  // namespace fleetmap::lcmtypes
