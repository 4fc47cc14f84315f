// The edge between LCM messages and the libraries' types, shared by every process: each
// FromMessage validates what came from the network (sizes, NaN, limits) and returns a Status
// instead of handing garbage on; Decode catches what LCM's generated decoders throw on
// corrupt lengths. Default URLs live here too; channel names in lcmtypes/channels.h.
#pragma once

#include <string>

#include "core/odometry.h"
#include "core/scan.h"
#include "fleetmap/laser_scan_t.hpp"
#include "fleetmap/odometry_t.hpp"
#include "fleetmap/pose_with_covariance_t.hpp"
#include "lcmtypes/channels.h"

namespace fleetmap::lcmtypes {

// Uplink (vehicles to aggregator), downlink (aggregator to vehicles) and on-vehicle sensor
// traffic use separate multicast groups, so that nobody receives what it would only drop
// (docs/channels.md, "What LCM needs"). ttl=0 keeps traffic on the host; across hosts use
// ttl=1.
constexpr const char* kDefaultSensorUrl = "udpm://239.255.76.69:7669?ttl=0";
constexpr const char* kDefaultUplinkUrl = "udpm://239.255.76.67:7667?ttl=0";
constexpr const char* kDefaultDownlinkUrl = "udpm://239.255.76.68:7668?ttl=0";

// A scan may have at most this many beams (an LMS511 at 1/6 deg has 1141; 0.1 deg over 360
// deg is 3600).
constexpr int kMaxBeams = 10000;

// A vehicle id from the network: 1 to 64 printable ASCII characters. Ids become channel names,
// and LCM encodes a string only up to its first NUL, so an id with a NUL, a space or a control
// character could be accepted but never answered.
core::Status CheckVehicleId(const std::string& id);

int64_t ToUtime(double stamp_s);
double FromUtime(int64_t utime);

// Poses unchecked: callers check IsFinite() where a pose comes from outside.
fleetmap::pose2d_t ToMessage(const core::Pose2& pose);
core::Pose2 FromMessage(const fleetmap::pose2d_t& msg);

fleetmap::laser_scan_t ToMessage(const core::LaserScan& scan, const std::string& vehicle_id,
                                 int32_t seq);
core::Result<core::LaserScan> FromMessage(const fleetmap::laser_scan_t& msg);

fleetmap::odometry_t ToMessage(const core::OdometrySample& odom, const std::string& vehicle_id);
core::Result<core::OdometrySample> FromMessage(const fleetmap::odometry_t& msg);

// A pose covariance as the messages carry it: 9 doubles, row-major.
void ToRowMajor(const Eigen::Matrix3d& covariance, double (&out)[9]);
Eigen::Matrix3d FromRowMajor(const double (&in)[9]);

fleetmap::pose_with_covariance_t ToMessage(const core::PoseEstimate& pose,
                                           const std::string& vehicle_id);
core::Result<core::PoseEstimate> FromMessage(const fleetmap::pose_with_covariance_t& msg);

// Decodes an LCM payload of type T. Truncated data, another type, trailing bytes and the
// exceptions LCM's decoders throw on corrupt length fields all become DataLoss.
template <typename T>
core::Result<T> Decode(const void* data, int size) {
  T msg;
  try {
    const int used = msg.decode(data, 0, size);
    if (used < 0) return core::DataLoss("malformed or truncated " + std::string(T::getTypeName()));
    if (used != size) {
      return core::DataLoss(std::string(T::getTypeName()) + " followed by " +
                            std::to_string(size - used) + " unexpected bytes");
    }
  } catch (const std::exception& e) {
    return core::DataLoss(std::string(T::getTypeName()) + " with a corrupt length: " + e.what());
  }
  return msg;
}

}  // namespace fleetmap::lcmtypes
