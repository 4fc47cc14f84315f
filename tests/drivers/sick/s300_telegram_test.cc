#include "drivers/sick/s300_telegram.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <thread>

#include "drivers/sick/serial_port.h"
#include "sim/sick/s300_output.h"
#include "sim/sick/scan_source.h"
#include "tests/drivers/sick/sick_test_util.h"

namespace fleetmap::drivers::sick {
namespace {

S300Telegram Sample(size_t beams = 541) {
  S300Telegram t;
  t.scan_number = 0x01020304;
  t.telegram_number = 9;
  for (size_t i = 0; i < beams; ++i) t.beams.push_back(static_cast<uint16_t>(100 + i));
  t.beams[3] |= 0x2000 | 0x8000;  // reflector, warning field
  return t;
}

TEST(S300TelegramTest, CrcIsCcittFalse) {
  const std::string check = "123456789";
  EXPECT_EQ(Crc16Ccitt(reinterpret_cast<const uint8_t*>(check.data()), check.size()), 0x29B1);
}

TEST(S300TelegramTest, LayoutMatchesTheProtocolFacts) {
  const std::vector<uint8_t> bytes = EncodeS300Telegram(Sample());
  ASSERT_EQ(bytes.size(), 1108u);  // 24 header + 541 * 2 + 2 CRC
  EXPECT_EQ(bytes[6], 0x02);       // size 552 words = 0x0228, big-endian
  EXPECT_EQ(bytes[7], 0x28);
  EXPECT_EQ(bytes[8], 0xFF);
  EXPECT_EQ(bytes[9], 0x07);
  EXPECT_EQ(bytes[20], 0xBB);
  EXPECT_EQ(bytes[22], 0x11);
  EXPECT_EQ(bytes[24], 100);  // first beam, little-endian
  EXPECT_EQ(bytes[25], 0);
  const uint16_t crc = Crc16Ccitt(bytes.data() + 4, bytes.size() - 6);
  EXPECT_EQ(bytes[1106], crc & 0xFF);
  EXPECT_EQ(bytes[1107], crc >> 8);
  core::Result<S300Telegram> t = ParseS300Telegram(bytes.data(), bytes.size());
  ASSERT_TRUE(t.ok()) << t.status().ToString();
  EXPECT_EQ(t->scan_number, 0x01020304u);
  EXPECT_EQ(S300Telegram::DistanceCm(t->beams[3]), 103);
  EXPECT_TRUE(S300Telegram::Reflector(t->beams[3]));
  EXPECT_TRUE(S300Telegram::WarningField(t->beams[3]));
  EXPECT_FALSE(S300Telegram::ProtectiveField(t->beams[3]));
}

TEST(S300TelegramTest, BadCrcAndSizesAreRejected) {
  std::vector<uint8_t> bytes = EncodeS300Telegram(Sample());
  bytes[500] ^= 0x10;
  EXPECT_EQ(ParseS300Telegram(bytes.data(), bytes.size()).status().code(),
            core::StatusCode::kDataLoss);
  EXPECT_FALSE(ParseS300Telegram(bytes.data(), 100).ok());
}

TEST(S300TelegramTest, SplitterResynchronisesAfterGarbageAndBadCrc) {
  std::vector<uint8_t> good = EncodeS300Telegram(Sample());
  std::vector<uint8_t> bad = good;
  bad[700] ^= 1;
  std::vector<uint8_t> stream = {1, 2, 3, 0, 0, 0};
  stream.insert(stream.end(), bad.begin(), bad.end());
  stream.insert(stream.end(), good.begin(), good.end());
  stream.insert(stream.end(), {0, 0, 0, 0, 0, 0, 0xFF, 0xFF, 0xFF});  // size field 0xFFFF
  stream.insert(stream.end(), good.begin(), good.end());
  S300StreamSplitter s;
  int got = 0;
  for (size_t at = 0; at < stream.size(); at += 100) {
    s.Feed(stream.data() + at, std::min<size_t>(100, stream.size() - at));
    while (s.Next()) ++got;
    EXPECT_LT(s.buffered_bytes(), 1108u + 2 * 2000 + 100);
  }
  EXPECT_EQ(got, 2);
  EXPECT_GE(s.stats().bad_crc, 1u);
  EXPECT_GE(s.stats().bad_size, 1u);
  EXPECT_GT(s.stats().garbage_bytes, 0u);
}

TEST(S300TelegramTest, ToLaserScanSpans270Degrees) {
  core::Result<core::LaserScan> scan = S300ToLaserScan(Sample(), S300ScanOptions(), 1.0);
  ASSERT_TRUE(scan.ok());
  EXPECT_EQ(scan->size(), 541u);
  EXPECT_NEAR(scan->angle_min_rad, -135.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(scan->angle_increment_rad, 0.5 * M_PI / 180.0, 1e-12);
  EXPECT_FLOAT_EQ(scan->ranges_m[0], 1.0f);
}

// The emulator writes S300 telegrams into a pseudo-terminal; the driver reads them through
// termios (raw mode, 500 kBaud) like a USB RS-422 adapter.
TEST(S300SerialTest, ReadsTheEmulatorsTelegramsFromAPseudoTerminal) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(grantpt(master), 0);
  ASSERT_EQ(unlockpt(master), 0);
  core::Result<SerialPort> port = SerialPort::Open(ptsname(master), 500000);
  ASSERT_TRUE(port.ok()) << port.status().ToString();
  S300SerialReader reader(std::move(port).value());
  std::vector<ScanTelegram> scans;
  for (int i = 0; i < 5; ++i) {
    ScanTelegram t = testing::Tim781Like(false);
    t.scan_counter = static_cast<uint16_t>(i + 1);
    t.channels16[0].values[0] = static_cast<uint16_t>(1000 + 10 * i);  // 1.00 m, 1.01 m, ...
    scans.push_back(t);
  }
  sim::sick::RecordingScanSource source(scans, /*loop=*/false);
  std::thread writer([&] { EXPECT_EQ(*sim::sick::WriteS300Stream(source, master, 5), 5u); });
  for (int i = 0; i < 5; ++i) {
    core::Result<S300Telegram> t = reader.Next(5.0);
    ASSERT_TRUE(t.ok()) << t.status().ToString();
    EXPECT_EQ(t->scan_number, static_cast<uint32_t>(i + 1));
    ASSERT_EQ(t->beams.size(), 541u);
    EXPECT_EQ(S300Telegram::DistanceCm(t->beams[0]), 100 + i);
  }
  writer.join();
  EXPECT_EQ(reader.stats().bad_crc, 0u);
  close(master);
  EXPECT_FALSE(SerialPort::Open("/dev/null", 12345).ok());
}

}  // namespace
}  // namespace fleetmap::drivers::sick
