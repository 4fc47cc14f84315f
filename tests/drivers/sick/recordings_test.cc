// Every scan telegram recorded from real SICK scanners (the data folder's sick/, SOURCES.md there)
// parses, with the device's point count, angles and frequency, correct checksums, and ranges
// that match values read by hand from the files' hex.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "drivers/sick/scan_conversion.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "sim/sick/recording_reader.h"
#include "tests/support/data_dir.h"

namespace fleetmap::drivers::sick {
namespace {

std::string SickData(const std::string& file) { return testing::DataPath("sick/" + file); }

struct DeviceFacts {
  const char* file;
  size_t scans;  // scan telegrams in the file
  ColaProtocol protocol;
  size_t points;
  double start_deg;  // SICK angle of the first point
  double step_deg;
  double frequency_hz;
  bool rssi_8bit;  // RSSI1 present as an 8-bit channel
  bool rssi_16bit;
};

const DeviceFacts kDevices[] = {
    {"sick_scan_xd/test.pcapng", 16, ColaProtocol::kColaB, 811, -45, 1 / 3.0, 15, false, true},
    {"sick_scan_xd/example.pcapng", 766, ColaProtocol::kColaB, 811, -45, 1 / 3.0, 15, false, true},
    {"sick_scan_xd/20210302_lms111.pcapng.json", 175, ColaProtocol::kColaB, 541, -45, 0.5, 50,
     false, false},
    {"sick_scan_xd/20210302_lms511.pcapng.json", 174, ColaProtocol::kColaB, 1141, -5, 1 / 6.0, 25,
     true, false},
    {"sick_scan_xd/20210125-tim781s-scandata.pcapng.json", 140, ColaProtocol::kColaB, 811, -45,
     1 / 3.0, 15, false, true},
    {"pysicktim/sim.dat", 51, ColaProtocol::kColaA, 811, -45, 1 / 3.0, 15, false, false},
};

class RecordingsTest : public ::testing::TestWithParam<DeviceFacts> {};

TEST_P(RecordingsTest, EveryScanParsesWithTheDevicesGeometry) {
  const DeviceFacts& d = GetParam();
  FLEETMAP_SKIP_WITHOUT_DATA(std::string("sick/") + d.file);
  core::Result<sim::sick::Recording> recording = sim::sick::ReadRecording(SickData(d.file));
  ASSERT_TRUE(recording.ok()) << recording.status().ToString();
  EXPECT_EQ(recording->framing.bad_checksums, 0u);
  EXPECT_EQ(recording->framing.oversized, 0u);
  const auto scans = sim::sick::ScanTelegrams(*recording);
  ASSERT_EQ(scans.size(), d.scans);
  for (const sim::sick::RecordedTelegram& r : scans) {
    ASSERT_EQ(r.protocol, d.protocol);
    core::Result<ScanTelegram> t = ParseScanTelegram(r.payload, r.protocol);
    ASSERT_TRUE(t.ok()) << t.status().ToString();
    const ScanChannel* dist = t->FindChannel("DIST1");
    ASSERT_NE(dist, nullptr);
    EXPECT_EQ(dist->values.size(), d.points);
    EXPECT_NEAR(dist->start_angle_deg(), d.start_deg, 1e-3);
    EXPECT_NEAR(dist->angular_step_deg(), d.step_deg, 1e-3);
    EXPECT_DOUBLE_EQ(t->scan_frequency_hz(), d.frequency_hz);
    const ScanChannel* rssi = t->FindChannel("RSSI1");
    EXPECT_EQ(rssi != nullptr, d.rssi_8bit || d.rssi_16bit);
    EXPECT_EQ(t->channels8.size(), d.rssi_8bit ? 1u : 0u);
    if (rssi != nullptr) {
      EXPECT_EQ(rssi->values.size(), d.points);
    }
    // The whole field of view: e.g. 270 degrees for 811 points at 1/3 degree.
    core::Result<core::LaserScan> scan = ToLaserScan(*t, ScanConversionOptions(), 0.0);
    ASSERT_TRUE(scan.ok()) << scan.status().ToString();
    EXPECT_NEAR(scan->angle_min_rad, (d.start_deg - 90.0) * M_PI / 180.0, 1e-4);
    EXPECT_NEAR(scan->scan_period_s, 1.0 / d.frequency_hz, 1e-9);
    EXPECT_TRUE(scan->Validate().ok());
  }
}

INSTANTIATE_TEST_SUITE_P(RealScanners, RecordingsTest, ::testing::ValuesIn(kDevices),
                         [](const auto& info) { return "Device" + std::to_string(info.index); });

// The first scan of each file, with values read by hand from its hex dump. Skips when the
// recording is absent; a recording that does not parse fails the test (never read further).
class RecordingsSpotCheckTest : public ::testing::Test {
 protected:
  // Fills *t with the first scan of `file`; the caller returns when it fails or skips.
  void FirstScan(const std::string& file, ScanTelegram* t) {
    FLEETMAP_SKIP_WITHOUT_DATA("sick/" + file);
    core::Result<sim::sick::Recording> recording = sim::sick::ReadRecording(SickData(file));
    ASSERT_TRUE(recording.ok()) << recording.status().ToString();
    const auto scans = sim::sick::ScanTelegrams(*recording);
    ASSERT_FALSE(scans.empty());
    core::Result<ScanTelegram> parsed =
        ParseScanTelegram(scans.front().payload, scans.front().protocol);
    ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
    ASSERT_NE(parsed->FindChannel("DIST1"), nullptr);
    *t = std::move(parsed).value();
  }
};

// Reads the first scan of FILE into `t`, or leaves the test (skipped or failed).
#define FIRST_SCAN_OR_RETURN(file) \
  ScanTelegram t;                  \
  FirstScan(file, &t);             \
  if (IsSkipped() || HasFatalFailure()) return

TEST_F(RecordingsSpotCheckTest, Lms111RangesAndHeader) {
  FIRST_SCAN_OR_RETURN("sick_scan_xd/20210302_lms111.pcapng.json");
  EXPECT_EQ(t.serial_number, 18090362u);  // 01 14 09 7A
  EXPECT_EQ(t.scan_counter, 4u);
  const ScanChannel& d = *t.FindChannel("DIST1");
  EXPECT_EQ(d.values[0], 93);  // 00 5D
  EXPECT_EQ(d.values[1], 80);
  EXPECT_EQ(d.values[270], 1339);  // straight ahead: 1.339 m
  EXPECT_EQ(d.values[540], 77);
  ASSERT_TRUE(t.clock.has_value());  // time block: 07 B2 01 01 02 37 22 00 0D 90 A8
  EXPECT_EQ(t.clock->year, 1970);
  EXPECT_EQ(t.clock->hour, 2);
  EXPECT_EQ(t.clock->minute, 0x37);
  EXPECT_EQ(t.clock->microsecond, 0x0D90A8u);
  EXPECT_FALSE(t.event.has_value());
}

TEST_F(RecordingsSpotCheckTest, Lms511HeaderVersionZeroAnd8BitRssi) {
  FIRST_SCAN_OR_RETURN("sick_scan_xd/20210302_lms511.pcapng.json");
  EXPECT_EQ(t.version, 0);
  EXPECT_EQ(t.serial_number, 18110550u);
  const ScanChannel& d = *t.FindChannel("DIST1");
  EXPECT_EQ(d.values[0], 1305);
  EXPECT_EQ(d.values[270], 1122);
  EXPECT_EQ(d.values[1140], 624);
  EXPECT_EQ(t.channels8.at(0).content, "RSSI1");
}

TEST_F(RecordingsSpotCheckTest, Tim781sRanges) {
  FIRST_SCAN_OR_RETURN("sick_scan_xd/20210125-tim781s-scandata.pcapng.json");
  const ScanChannel& d = *t.FindChannel("DIST1");
  EXPECT_EQ(d.values[0], 1356);
  EXPECT_EQ(d.values[2], 1435);
  EXPECT_EQ(d.values[270], 1399);
  EXPECT_EQ(d.values[810], 662);
}

TEST_F(RecordingsSpotCheckTest, Tim561ColaANameBlock) {
  FIRST_SCAN_OR_RETURN("pysicktim/sim.dat");
  EXPECT_EQ(t.serial_number, 0x1078AAAu);
  EXPECT_EQ(t.time_since_startup_us, 0x3FFD3D6Cu);
  EXPECT_EQ(t.output_status[0], 1);
  const ScanChannel& d = *t.FindChannel("DIST1");
  EXPECT_EQ(d.values[0], 0x63E);  // 1.598 m
  EXPECT_EQ(d.values[1], 0x657);
  EXPECT_EQ(d.values[405], 924);
  EXPECT_EQ(d.values[810], 1109);
  ASSERT_TRUE(t.name.has_value());
  EXPECT_EQ(*t.name, "Daniyal");
  EXPECT_FALSE(t.comment.has_value());
  EXPECT_FALSE(t.clock.has_value());
  core::Result<core::LaserScan> scan = ToLaserScan(t, ScanConversionOptions(), 0.0);
  ASSERT_TRUE(scan.ok());
  EXPECT_FLOAT_EQ(scan->ranges_m[0], 1.598f);
}

TEST_F(RecordingsSpotCheckTest, PcapngSegmentsAreReassembled) {
  // Every 3374-byte telegram arrives as 1448 + 1926 bytes; all 16 come out whole.
  FLEETMAP_SKIP_WITHOUT_DATA("sick/sick_scan_xd/test.pcapng");
  core::Result<sim::sick::Recording> r =
      sim::sick::ReadRecording(SickData("sick_scan_xd/test.pcapng"));
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  ASSERT_EQ(sim::sick::ScanTelegrams(*r).size(), 16u);
  for (const auto& t : sim::sick::ScanTelegrams(*r)) EXPECT_EQ(t.payload.size() + 9, 3374u);
  EXPECT_EQ(r->framing.garbage_bytes, 0u);
}

TEST_F(RecordingsSpotCheckTest, RadarColaAStartupIsReadWithoutScans) {
  FLEETMAP_SKIP_WITHOUT_DATA("sick/sick_scan_xd/20221018_rms_1xxx_ascii_rms2_objects.pcapng.json");
  core::Result<sim::sick::Recording> r = sim::sick::ReadRecording(
      SickData("sick_scan_xd/20221018_rms_1xxx_ascii_rms2_objects.pcapng.json"));
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  ASSERT_FALSE(r->telegrams.empty());
  EXPECT_EQ(r->telegrams.front().protocol, ColaProtocol::kColaA);
  bool login = false, granted = false;
  for (const auto& t : r->telegrams) {
    login |= t.payload == "sMN SetAccessMode 3 F4724744" && !t.from_scanner;
    granted |= t.payload == "sAN SetAccessMode 1" && t.from_scanner;
  }
  EXPECT_TRUE(login);
  EXPECT_TRUE(granted);
  EXPECT_TRUE(sim::sick::ScanTelegrams(*r).empty());  // LMDradardata, not LMDscandata
}

}  // namespace
}  // namespace fleetmap::drivers::sick
