#include "drivers/sick/scan_telegram_codec.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/sick/scan_conversion.h"
#include "tests/drivers/sick/sick_test_util.h"

namespace fleetmap::drivers::sick {
namespace {

void ExpectSame(const ScanTelegram& a, const ScanTelegram& b) {
  EXPECT_EQ(a.serial_number, b.serial_number);
  EXPECT_EQ(a.scan_counter, b.scan_counter);
  EXPECT_EQ(a.time_since_startup_us, b.time_since_startup_us);
  EXPECT_EQ(a.scan_frequency_centihz, b.scan_frequency_centihz);
  ASSERT_EQ(a.encoders.size(), b.encoders.size());
  for (size_t i = 0; i < a.encoders.size(); ++i) {
    EXPECT_EQ(a.encoders[i].position_ticks, b.encoders[i].position_ticks);
  }
  ASSERT_EQ(a.channels16.size(), b.channels16.size());
  ASSERT_EQ(a.channels8.size(), b.channels8.size());
  for (size_t i = 0; i < a.channels16.size(); ++i) {
    EXPECT_EQ(a.channels16[i].content, b.channels16[i].content);
    EXPECT_EQ(a.channels16[i].start_angle_1e4deg, b.channels16[i].start_angle_1e4deg);
    EXPECT_EQ(a.channels16[i].values, b.channels16[i].values);
  }
  for (size_t i = 0; i < a.channels8.size(); ++i)
    EXPECT_EQ(a.channels8[i].values, b.channels8[i].values);
  EXPECT_EQ(a.position.has_value(), b.position.has_value());
  if (a.position) {
    EXPECT_FLOAT_EQ(a.position->z_rot, b.position->z_rot);
  }
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.comment, b.comment);
  EXPECT_EQ(a.clock.has_value(), b.clock.has_value());
  if (a.clock) {
    EXPECT_EQ(a.clock->microsecond, b.clock->microsecond);
  }
  EXPECT_EQ(a.event.has_value(), b.event.has_value());
  if (a.event) {
    EXPECT_EQ(a.event->angular_position_1e4deg, b.event->angular_position_1e4deg);
  }
}

class CodecTest : public ::testing::TestWithParam<ColaProtocol> {};

TEST_P(CodecTest, RoundTripKeepsEveryField) {
  for (const bool all_blocks : {false, true}) {
    const ScanTelegram t = testing::Tim781Like(all_blocks);
    const std::string payload = EncodeScanTelegram(t, GetParam(), "sRA");
    EXPECT_TRUE(IsScanTelegram(payload));
    core::Result<ScanTelegram> back = ParseScanTelegram(payload, GetParam());
    ASSERT_TRUE(back.ok()) << back.status().ToString();
    ExpectSame(t, *back);
  }
}

TEST_P(CodecTest, EveryTruncationIsAnErrorNotACrash) {
  const std::string payload = EncodeScanTelegram(testing::Tim781Like(), GetParam());
  // Cut at every length (coarser for the long value arrays). CoLa-A has no length field: a
  // cut inside the last token is still a number, so cuts stop before it (ETX frames it).
  const size_t end = GetParam() == ColaProtocol::kColaA ? payload.rfind(' ') : payload.size();
  for (size_t n = 0; n < end; n += (n < 200 || n > end - 200) ? 1 : 97) {
    core::Result<ScanTelegram> t = ParseScanTelegram(payload.substr(0, n), GetParam());
    EXPECT_FALSE(t.ok()) << "cut at " << n;
  }
}

INSTANTIATE_TEST_SUITE_P(BothProtocols, CodecTest,
                         ::testing::Values(ColaProtocol::kColaA, ColaProtocol::kColaB));

TEST(CodecTest, CountsLargerThanTheTelegramAreRefusedBeforeAllocating) {
  ScanTelegram t = testing::Tim781Like(false);
  std::string payload = EncodeScanTelegram(t, ColaProtocol::kColaB);
  // The DIST1 count sits 2 bytes before its values: claim 65535 values.
  const size_t count_at = payload.find("DIST1") + 5 + 4 + 4 + 4 + 2;
  payload[count_at] = '\xff';
  payload[count_at + 1] = '\xff';
  core::Result<ScanTelegram> r = ParseScanTelegram(payload, ColaProtocol::kColaB);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("more than the telegram holds"), std::string::npos);
}

TEST(CodecTest, BadFlagsAndCountsNameTheField) {
  std::string payload = EncodeScanTelegram(testing::Tim781Like(false), ColaProtocol::kColaA);
  // The trailer is "... 0 0 0 0 0" (position, name, comment, time, event): make the name flag 7.
  payload[payload.size() - 7] = '7';
  core::Result<ScanTelegram> r = ParseScanTelegram(payload, ColaProtocol::kColaA);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("name flag"), std::string::npos) << r.status().ToString();
  EXPECT_FALSE(ParseScanTelegram("sRA LMDscandatacfg 1", ColaProtocol::kColaA).ok());
  EXPECT_FALSE(ParseScanTelegram("garbage", ColaProtocol::kColaA).ok());
}

TEST(CodecTest, AsciiAcceptsDecimalSignedAngles) {
  // A start angle written "-450000" (decimal with sign) equals the hex FFF92230.
  std::string payload = EncodeScanTelegram(testing::Tim781Like(false), ColaProtocol::kColaA);
  const size_t at = payload.find("FFF92230");
  ASSERT_NE(at, std::string::npos);
  payload.replace(at, 8, "-450000");
  core::Result<ScanTelegram> t = ParseScanTelegram(payload, ColaProtocol::kColaA);
  ASSERT_TRUE(t.ok()) << t.status().ToString();
  EXPECT_EQ(t->channels16[0].start_angle_1e4deg, -450000);
}

TEST(ScanConversionTest, AnglesRangesAndNoEcho) {
  ScanTelegram t = testing::Tim781Like(false);
  t.channels16[0].values[5] = 0;  // no echo
  ScanConversionOptions tim;
  tim.range_max_m = 25.0;  // TiM781S: DIST1 in plain mm (scale 1)
  core::Result<core::LaserScan> scan = ToLaserScan(t, tim, 12.5);
  ASSERT_TRUE(scan.ok());
  EXPECT_EQ(scan->size(), 811u);
  EXPECT_NEAR(scan->angle_min_rad, -135.0 * M_PI / 180.0, 1e-9);
  EXPECT_NEAR(scan->angle(810), 135.0 * M_PI / 180.0, 1e-3);
  EXPECT_FLOAT_EQ(scan->ranges_m[0], 1.0f);
  EXPECT_TRUE(std::isinf(scan->ranges_m[5]));
  EXPECT_EQ(scan->intensities.size(), 811u);
  EXPECT_DOUBLE_EQ(scan->stamp_s, 12.5);
  // And back: FromLaserScan reproduces DIST1.
  const ScanTelegram again = FromLaserScan(*scan);
  EXPECT_EQ(again.channels16[0].start_angle_1e4deg, -450000);
  EXPECT_EQ(again.channels16[0].values, t.channels16[0].values);
  ScanConversionOptions no_channel;
  no_channel.range_channel = "DIST2";
  EXPECT_FALSE(ToLaserScan(t, no_channel, 0.0).ok());
}

}  // namespace
}  // namespace fleetmap::drivers::sick
