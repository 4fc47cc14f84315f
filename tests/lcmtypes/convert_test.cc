#include "lcmtypes/convert.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace fleetmap::lcmtypes {
namespace {

using ::testing::HasSubstr;

core::LaserScan Scan() {
  core::LaserScan s;
  s.stamp_s = 1700000000.25;
  s.angle_min_rad = -2.35619;
  s.angle_increment_rad = 0.00872665;
  s.range_min_m = 0.05;
  s.range_max_m = 30.0;
  s.scan_period_s = 0.04;
  s.ranges_m.assign(541, 4.5f);
  s.ranges_m[10] = INFINITY;  // no return
  s.ranges_m[11] = NAN;       // a corrupt beam is an invalid return, not an invalid scan
  return s;
}

template <typename T>
std::vector<uint8_t> Encode(const T& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  EXPECT_EQ(msg.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

TEST(ConvertTest, ScanRoundTripThroughBytes) {
  const auto bytes = Encode(ToMessage(Scan(), "cts1", 7));
  auto msg = Decode<fleetmap::laser_scan_t>(bytes.data(), static_cast<int>(bytes.size()));
  ASSERT_TRUE(msg.ok()) << msg.status().ToString();
  EXPECT_EQ(msg->seq, 7);
  auto scan = FromMessage(*msg);
  ASSERT_TRUE(scan.ok()) << scan.status().ToString();
  EXPECT_NEAR(scan->stamp_s, 1700000000.25, 1e-6);
  ASSERT_EQ(scan->size(), 541u);
  EXPECT_FALSE(scan->IsValidReturn(10));
  EXPECT_FALSE(scan->IsValidReturn(11));
  EXPECT_TRUE(scan->IsValidReturn(12));
}

TEST(ConvertTest, RejectsScansThatAreNotScans) {
  auto msg = ToMessage(Scan(), "cts1", 0);
  msg.angle_increment_rad = 0;
  EXPECT_THAT(FromMessage(msg).status().message(), HasSubstr("non-zero increment"));
  msg = ToMessage(Scan(), "cts1", 0);
  msg.range_max_m = NAN;
  EXPECT_FALSE(FromMessage(msg).ok());
  msg = ToMessage(Scan(), "", 0);
  EXPECT_THAT(FromMessage(msg).status().message(), HasSubstr("vehicle_id"));
  core::LaserScan huge = Scan();
  huge.ranges_m.assign(kMaxBeams + 1, 1.0f);
  huge.angle_increment_rad = 1e-4;
  EXPECT_EQ(FromMessage(ToMessage(huge, "cts1", 0)).status().code(), core::StatusCode::kOutOfRange);
}

TEST(ConvertTest, DecodeRejectsTruncatedForeignAndPaddedBytes) {
  auto bytes = Encode(ToMessage(Scan(), "cts1", 0));
  for (size_t n : {size_t{0}, size_t{8}, bytes.size() / 2, bytes.size() - 1}) {
    EXPECT_FALSE(Decode<fleetmap::laser_scan_t>(bytes.data(), static_cast<int>(n)).ok()) << n;
  }
  const auto odom = Encode(ToMessage(core::OdometrySample{1.0, {}, 0.5, 0.0}, "cts1"));
  EXPECT_FALSE(Decode<fleetmap::laser_scan_t>(odom.data(), static_cast<int>(odom.size())).ok());
  bytes.push_back(0);
  EXPECT_THAT(Decode<fleetmap::laser_scan_t>(bytes.data(), static_cast<int>(bytes.size()))
                  .status()
                  .message(),
              HasSubstr("unexpected bytes"));
}

TEST(ConvertTest, DecodeSurvivesACorruptLengthField) {
  auto bytes = Encode(ToMessage(Scan(), "cts1", 0));
  // The string length of vehicle_id sits right after the 8-byte fingerprint and the 8-byte
  // utime: zero makes LCM's decoder throw, which must become a status.
  for (int i = 16; i < 20; ++i) bytes[static_cast<size_t>(i)] = 0;
  const auto r = Decode<fleetmap::laser_scan_t>(bytes.data(), static_cast<int>(bytes.size()));
  EXPECT_EQ(r.status().code(), core::StatusCode::kDataLoss);
}

TEST(ConvertTest, OdometryAndPoseRoundTrip) {
  const core::OdometrySample odom{12.5, core::Pose2(1, 2, 0.3), 0.5, -0.1};
  auto o = FromMessage(ToMessage(odom, "v"));
  ASSERT_TRUE(o.ok());
  EXPECT_DOUBLE_EQ(o->pose_in_odom.theta_rad, 0.3);
  core::PoseEstimate pose;
  pose.stamp_s = 3;
  pose.pose_in_map = core::Pose2(4, 5, 6 - 2 * M_PI);
  pose.covariance = Eigen::Vector3d(0.01, 0.02, 0.001).asDiagonal();
  pose.covariance(0, 1) = pose.covariance(1, 0) = 0.005;
  pose.map_version = 9;
  auto p = FromMessage(ToMessage(pose, "v"));
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->map_version, 9);
  EXPECT_DOUBLE_EQ(p->covariance(1, 0), 0.005);
  auto bad = ToMessage(pose, "v");
  bad.covariance[1] = 1.0;  // not symmetric
  EXPECT_FALSE(FromMessage(bad).ok());
  auto nan = ToMessage(odom, "v");
  nan.v_mps = NAN;
  EXPECT_FALSE(FromMessage(nan).ok());
}

}  // namespace
}  // namespace fleetmap::lcmtypes
