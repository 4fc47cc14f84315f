#include "drivers/can/diff_drive_odometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/can/diff_drive_can_encoder.h"
#include "drivers/can/socketcan.h"
#include "sim/can/sim_can_log.h"
#include "tests/drivers/can/can_test_world.h"

namespace fleetmap::drivers::can {
namespace {

CanFrame Frame(uint32_t id, std::initializer_list<uint8_t> data, double t = 0.0) {
  CanFrame f;
  f.id = id;
  f.stamp_s = t;
  f.len = static_cast<uint8_t>(data.size());
  std::copy(data.begin(), data.end(), f.data.begin());
  return f;
}

CanFrame Position(uint32_t id, int32_t ticks, double t) {
  const uint32_t u = static_cast<uint32_t>(ticks);
  return Frame(id, {uint8_t(u), uint8_t(u >> 8), uint8_t(u >> 16), uint8_t(u >> 24)}, t);
}

DiffDriveCanOptions Options() {
  DiffDriveCanOptions o;
  o.wheel_radius_m = 0.1;
  o.ticks_per_revolution = 1000;
  o.gear_ratio = 1.0;
  o.track_width_m = 0.5;
  return o;
}

TEST(DiffDriveOdometryTest, StraightDriveAcrossTheInt32WrapAround) {
  DiffDriveOdometry odo(Options());
  const int32_t start = INT32_MAX - 500;
  // One wheel revolution (1000 ticks = 0.2 pi m) per 0.1 s cycle, wrapping after half of it.
  std::optional<core::OdometrySample> s;
  for (int k = 0; k <= 2; ++k) {
    const double t = 10.0 + 0.1 * k;
    const int32_t ticks = static_cast<int32_t>(static_cast<uint32_t>(start) + 1000u * k);
    EXPECT_FALSE(odo.Decode(Frame(0x80, {}, t)));
    EXPECT_FALSE(odo.Decode(Position(0x181, ticks, t + 0.001)));
    s = odo.Decode(Position(0x182, ticks, t + 0.002));
    ASSERT_TRUE(s.has_value());
    EXPECT_DOUBLE_EQ(s->stamp_s, t);  // stamped with the SYNC
  }
  EXPECT_NEAR(s->pose_in_odom.x_m, 2 * 0.2 * M_PI, 1e-9);
  EXPECT_NEAR(s->pose_in_odom.y_m, 0.0, 1e-12);
  EXPECT_NEAR(s->v_mps, 0.2 * M_PI / 0.1, 1e-6);
  EXPECT_EQ(odo.stats().samples, 3u);
}

TEST(DiffDriveOdometryTest, TurnInPlaceAndInvertedRightMotor) {
  DiffDriveCanOptions o = Options();
  o.right.inverted = true;
  DiffDriveOdometry odo(o);
  odo.Decode(Frame(0x80, {}, 0.0));
  odo.Decode(Position(0x181, 0, 0.0));
  odo.Decode(Position(0x182, 0, 0.0));
  // Left wheel back, right wheel forward; the inverted right motor counts down.
  const double wheel_m = 0.25 * M_PI / 2;  // quarter turn of the vehicle: track/2 * pi/2
  const int32_t ticks = static_cast<int32_t>(std::lround(wheel_m / o.metres_per_tick()));
  odo.Decode(Frame(0x80, {}, 1.0));
  odo.Decode(Position(0x181, -ticks, 1.0));
  const auto s = odo.Decode(Position(0x182, -ticks, 1.0));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->pose_in_odom.theta_rad, M_PI / 2, 2e-3);
  EXPECT_NEAR(std::hypot(s->pose_in_odom.x_m, s->pose_in_odom.y_m), 0.0, 1e-9);
  EXPECT_NEAR(s->omega_radps, M_PI / 2, 2e-3);
}

TEST(DiffDriveOdometryTest, VelocityMappingIntegratesOverTheSyncPeriod) {
  DiffDriveCanOptions o = Options();
  o.left.object = o.right.object = DriveObject::kVelocity;
  o.left.scaling = o.right.scaling = 0.1;  // raw unit: 0.1 tick/s
  DiffDriveOdometry odo(o);
  const int32_t raw = static_cast<int32_t>(std::lround(0.5 / o.metres_per_tick() / 0.1));
  std::optional<core::OdometrySample> s;
  for (int k = 0; k <= 10; ++k) {
    odo.Decode(Frame(0x80, {}, 0.02 * k));
    odo.Decode(Position(0x181, raw, 0.02 * k));
    s = odo.Decode(Position(0x182, raw, 0.02 * k));
  }
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->v_mps, 0.5, 1e-3);
  EXPECT_NEAR(s->pose_in_odom.x_m, 0.5 * 0.2, 1e-3);
}

TEST(DiffDriveOdometryTest, BadFramesAreCountedAndSkipped) {
  DiffDriveOdometry odo(Options());
  EXPECT_FALSE(odo.Decode(Position(0x181, 5, 0.0)));          // before any SYNC
  EXPECT_FALSE(odo.Decode(Frame(0x80, {1, 2}, 0.0)));         // SYNC with 2 bytes
  EXPECT_FALSE(odo.Decode(Frame(0x80, {7}, 0.0)));            // SYNC with a counter: fine
  EXPECT_FALSE(odo.Decode(Frame(0x181, {1, 2, 3}, 0.0)));     // DLC 3 < 4
  EXPECT_FALSE(odo.Decode(Frame(0x183, {1, 2, 3, 4}, 0.0)));  // node 3: unknown
  EXPECT_FALSE(odo.Decode(Frame(0x703, {5}, 0.0)));           // heartbeat
  CanFrame error;
  error.error = true;
  error.id = 0x04;
  EXPECT_FALSE(odo.Decode(error));
  EXPECT_FALSE(odo.Decode(Position(0x181, 5, 0.0)));
  EXPECT_FALSE(odo.Decode(Position(0x181, 6, 0.0)));  // twice in one cycle
  EXPECT_FALSE(odo.Decode(Frame(0x80, {}, 0.1)));     // cycle closed without node 2
  const CanOdometryStats& s = odo.stats();
  EXPECT_EQ(s.out_of_cycle, 2u);
  EXPECT_EQ(s.wrong_dlc, 2u);
  EXPECT_EQ(s.unknown_nodes, 1u);
  EXPECT_EQ(s.other_frames, 1u);
  EXPECT_EQ(s.error_frames, 1u);
  EXPECT_EQ(s.incomplete_cycles, 1u);
  EXPECT_EQ(s.samples, 0u);
}

TEST(DiffDriveOdometryTest, DecodesTheSimulatorsOdometryFromItsOwnFrames) {
  sim::can::SimCanLogOptions options;
  options.duration_s = 20.0;
  options.start_ticks = -2147483648LL + 100;
  options.can.right.inverted = true;
  core::Result<sim::can::SimCanLog> log =
      sim::can::RecordOdometryAsCan(sim::can::testing::LoopWorld(), options);
  ASSERT_TRUE(log.ok()) << log.status().ToString();
  DiffDriveOdometry odo(options.can);
  size_t i = 0;
  const core::Pose2 origin = log->odometry.front().pose_in_odom;
  for (const CandumpRecord& r : log->records) {
    if (auto s = odo.Decode(r.frame)) {
      const core::Pose2 expected = core::Between(origin, log->odometry[i++].pose_in_odom);
      EXPECT_NEAR(s->pose_in_odom.x_m, expected.x_m, 2e-3);
      EXPECT_NEAR(s->pose_in_odom.y_m, expected.y_m, 2e-3);
    }
  }
  EXPECT_EQ(i, log->odometry.size());
  EXPECT_GT(i, 900u);  // 50 Hz for 20 s
}

TEST(DiffDriveCanOptionsTest, LoadsYamlAndNamesBadFields) {
  core::Result<DiffDriveCanOptions> o = ParseDiffDriveCanOptions(R"(
sync_cob_id: 0x80
wheel_radius_m: 0.125
gear_ratio: 24.5
ticks_per_revolution: 2048
track_width_m: 0.62
left: {node_id: 5, object: velocity, byte_offset: 2, scaling: 0.5}
right: {node_id: 6, tpdo_cob_id: 0x286, inverted: true}
)",
                                                                 "can.yaml");
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_EQ(o->sync_cob_id, 0x80u);
  EXPECT_EQ(o->left.cob_id(), 0x185u);
  EXPECT_EQ(o->left.object, DriveObject::kVelocity);
  EXPECT_EQ(o->left.byte_offset, 2);
  EXPECT_EQ(o->right.cob_id(), 0x286u);
  EXPECT_TRUE(o->right.inverted);
  EXPECT_DOUBLE_EQ(o->track_width_m, 0.62);
  core::Result<DiffDriveCanOptions> bad = ParseDiffDriveCanOptions("track_width_m: -1\n", "x.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("track_width_m"), std::string::npos);
  bad = ParseDiffDriveCanOptions("left: {object: torque}\n", "x.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("left.object"), std::string::npos);
  bad = ParseDiffDriveCanOptions("left: {node_id: 2}\n", "x.yaml");  // same as right
  EXPECT_FALSE(bad.ok());
}

TEST(SocketCanHostTest, OpeningWithoutAfCanSaysWhy) {
  SocketCanOptions o;
  o.interface = "fleetmapnone0";
  core::Result<SocketCan> s = SocketCan::Open(o);
  ASSERT_FALSE(s.ok());  // either no AF_CAN in the kernel, or no such interface
  EXPECT_TRUE(s.status().code() == core::StatusCode::kUnimplemented ||
              s.status().code() == core::StatusCode::kNotFound)
      << s.status().ToString();
}

}  // namespace
}  // namespace fleetmap::drivers::can
