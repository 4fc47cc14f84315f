// The sensors' way in: good input queued in order, bad input counted and left out.
#include "vehicle_agent/node/sensor_intake.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lcmtypes/convert.h"
#include "vehicle_agent/node/agent_messages.h"

namespace fleetmap::vehicle_agent::node {
namespace {

core::LaserScan Scan(double stamp_s) {
  core::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.angle_min_rad = -1.0;
  scan.angle_increment_rad = 0.01;
  scan.range_max_m = 30.0;
  scan.ranges_m.assign(100, 2.0f);
  return scan;
}

class SensorIntakeTest : public ::testing::Test {
 protected:
  SensorIntakeTest()
      : log_([](LogLevel, const std::string&) {}),
        checks_("v1", &log_, &counters_),
        intake_("v1", InputQueueOptions{}, &checks_) {}

  template <typename T>
  static std::vector<uint8_t> Bytes(const T& message) {
    return Encode(message);
  }

  CauseLog log_;
  AgentNodeCounters counters_;
  MessageChecks checks_;
  SensorIntake intake_;
};

TEST_F(SensorIntakeTest, QueuesEveryGoodInputInArrivalOrder) {
  const auto scan = Bytes(lcmtypes::ToMessage(Scan(1.0), "v1", 7));
  const auto odom = Bytes(
      lcmtypes::ToMessage(core::OdometrySample{1.1, core::Pose2(0.5, 0.0, 0.1), 0.4, 0.0}, "v1"));
  core::PoseEstimate pose;
  pose.stamp_s = 1.2;
  pose.pose_in_map = core::Pose2(3.0, 4.0, 0.2);
  pose.covariance = Eigen::Matrix3d::Identity() * 0.01;
  const auto external = Bytes(lcmtypes::ToMessage(pose, "v1"));

  intake_.OnOdometry(odom.data(), static_cast<int>(odom.size()));
  intake_.OnScan(scan.data(), static_cast<int>(scan.size()));
  intake_.OnExternalPose(external.data(), static_cast<int>(external.size()));
  intake_.OnDriverOdometry(core::OdometrySample{1.3, core::Pose2(0.6, 0.0, 0.1), 0.4, 0.0});
  intake_.OnDriverScan(Scan(1.4));
  EXPECT_EQ(intake_.queue().size(), 5u);

  const std::vector<SensorInput> taken = intake_.TakeAll();
  ASSERT_EQ(taken.size(), 5u);
  EXPECT_DOUBLE_EQ(std::get<core::OdometrySample>(taken[0]).pose_in_odom.x_m, 0.5);
  EXPECT_DOUBLE_EQ(std::get<core::LaserScan>(taken[1]).stamp_s, 1.0);
  EXPECT_EQ(std::get<core::LaserScan>(taken[1]).ranges_m.size(), 100u);
  EXPECT_DOUBLE_EQ(std::get<ExternalPoseInput>(taken[2]).pose.pose_in_map.y_m, 4.0);
  EXPECT_DOUBLE_EQ(std::get<core::OdometrySample>(taken[3]).stamp_s, 1.3);
  EXPECT_DOUBLE_EQ(std::get<core::LaserScan>(taken[4]).stamp_s, 1.4);
  EXPECT_TRUE(intake_.TakeAll().empty());
  EXPECT_EQ(counters_.malformed_messages, 0);
  EXPECT_EQ(counters_.wrong_vehicle, 0);
}

TEST_F(SensorIntakeTest, LeavesOutWhatDoesNotDecodeFailsItsChecksOrNamesAnotherVehicle) {
  const auto foreign = Bytes(lcmtypes::ToMessage(Scan(1.0), "v2", 0));
  intake_.OnScan(foreign.data(), static_cast<int>(foreign.size()));
  const auto good = Bytes(lcmtypes::ToMessage(Scan(1.0), "v1", 0));
  intake_.OnScan(good.data(), static_cast<int>(good.size()) - 3);  // cut short
  auto no_beams = lcmtypes::ToMessage(Scan(1.0), "v1", 0);
  no_beams.num_ranges = 0;
  no_beams.ranges_m.clear();
  const auto empty = Bytes(no_beams);
  intake_.OnScan(empty.data(), static_cast<int>(empty.size()));
  auto broken = lcmtypes::ToMessage(core::OdometrySample{1.0, core::Pose2(), 0.0, 0.0}, "v1");
  broken.pose.x_m = NAN;
  const auto odom = Bytes(broken);
  intake_.OnOdometry(odom.data(), static_cast<int>(odom.size()));
  core::LaserScan bad_scan = Scan(2.0);
  bad_scan.angle_increment_rad = 0.0;
  intake_.OnDriverScan(bad_scan);
  intake_.OnDriverOdometry(core::OdometrySample{NAN, core::Pose2(), 0.0, 0.0});

  EXPECT_EQ(intake_.queue().size(), 0u);
  EXPECT_EQ(counters_.wrong_vehicle, 1);
  EXPECT_EQ(counters_.malformed_messages, 5);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
