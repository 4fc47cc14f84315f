#include "vehicle_agent/node/sensor_intake.h"

#include "lcmtypes/channels.h"
#include "lcmtypes/convert.h"

namespace fleetmap::vehicle_agent::node {

SensorIntake::SensorIntake(std::string vehicle_id, const InputQueueOptions& queue,
                           MessageChecks* checks)
    : vehicle_id_(std::move(vehicle_id)), checks_(checks), queue_(queue) {}

void SensorIntake::OnScan(const void* data, int size) {
  const std::string channel = lcmtypes::ScanChannel(vehicle_id_);
  auto m = checks_->Decode<fleetmap::laser_scan_t>(channel, data, size);
  if (!m || !checks_->OurVehicle(channel, m->vehicle_id)) return;
  core::Result<core::LaserScan> scan = lcmtypes::FromMessage(*m);
  if (!scan.ok()) return checks_->Malformed(channel, scan.status());
  queue_.Push(std::move(scan).value());
}

void SensorIntake::OnOdometry(const void* data, int size) {
  const std::string channel = lcmtypes::OdomChannel(vehicle_id_);
  auto m = checks_->Decode<fleetmap::odometry_t>(channel, data, size);
  if (!m || !checks_->OurVehicle(channel, m->vehicle_id)) return;
  core::Result<core::OdometrySample> odom = lcmtypes::FromMessage(*m);
  if (!odom.ok()) return checks_->Malformed(channel, odom.status());
  queue_.Push(*odom);
}

void SensorIntake::OnExternalPose(const void* data, int size) {
  const std::string channel = lcmtypes::ExternalPoseChannel(vehicle_id_);
  auto m = checks_->Decode<fleetmap::pose_with_covariance_t>(channel, data, size);
  if (!m || !checks_->OurVehicle(channel, m->vehicle_id)) return;
  core::Result<core::PoseEstimate> pose = lcmtypes::FromMessage(*m);
  if (!pose.ok()) return checks_->Malformed(channel, pose.status());
  queue_.Push(ExternalPoseInput{*pose});
}

void SensorIntake::OnDriverScan(const core::LaserScan& scan) {
  const core::Status valid = scan.Validate();
  if (!valid.ok()) return checks_->Malformed("scanner", valid);
  queue_.Push(scan);
}

void SensorIntake::OnDriverOdometry(const core::OdometrySample& odom) {
  const core::Status valid = odom.Validate();
  if (!valid.ok()) return checks_->Malformed("odometry", valid);
  queue_.Push(odom);
}

}  // namespace fleetmap::vehicle_agent::node
