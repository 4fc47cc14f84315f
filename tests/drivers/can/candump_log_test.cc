#include "drivers/can/candump_log.h"

#include <gtest/gtest.h>

#include <map>

#include "tests/support/data_dir.h"

namespace fleetmap::drivers::can {
namespace {

TEST(CandumpLogTest, ReadsTheRealCarRecording) {
  FLEETMAP_SKIP_WITHOUT_DATA("can/SOC_Manual_candump-2022-04-06_125818.log");
  const std::string path = testing::DataPath("can/SOC_Manual_candump-2022-04-06_125818.log");
  core::Result<CandumpLog> log = ReadCandumpLog(path);
  ASSERT_TRUE(log.ok()) << log.status().ToString();
  EXPECT_EQ(log->stats.malformed, 0u);
  ASSERT_EQ(log->records.size(), 423u);
  std::map<uint32_t, int> lengths;
  for (const CandumpRecord& r : log->records) {
    EXPECT_EQ(r.interface, "can0");
    EXPECT_FALSE(r.frame.extended || r.frame.fd || r.frame.rtr || r.frame.error);
    lengths[r.frame.id] = r.frame.len;
  }
  EXPECT_EQ(lengths, (std::map<uint32_t, int>{{0x243, 8}, {0x33A, 8}, {0x33B, 2}}));
  const CanFrame& first =
      log->records.front().frame;  // (1649249898.730936) can0 243#00000000A0000400
  EXPECT_EQ(first.id, 0x243u);
  EXPECT_EQ(first.data[4], 0xA0);
  EXPECT_NEAR(first.stamp_s, 1649249898.730936, 1e-6);
  const double span = log->records.back().frame.stamp_s - first.stamp_s;
  EXPECT_NEAR(span, 140.0, 2.0);
  // Written back, every line is identical to the file's.
  EXPECT_EQ(FormatCandumpLine(log->records.front()),
            "(1649249898.730936) can0 243#00000000A0000400");
}

TEST(CandumpLogTest, EveryFrameKindRoundTrips) {
  for (const char* line :
       {"(0000000001.000001) vcan0 123#", "(0000000001.000001) vcan0 12345678#DEADBEEF",
        "(0000000001.000001) vcan0 123#R", "(0000000001.000001) vcan0 123#R4",
        "(0000000001.000001) vcan0 321##1000102030405060708090A0B",
        "(0000000001.000001) vcan0 20000080#0000000000000000",
        "(0000000001.000001) vcan0 123#1122334455667788_C"}) {
    core::Result<CandumpRecord> r = ParseCandumpLine(line);
    ASSERT_TRUE(r.ok()) << line << ": " << r.status().ToString();
    EXPECT_EQ(FormatCandumpLine(*r), line);
  }
  core::Result<CandumpRecord> e = ParseCandumpLine("(1.5) can1 20000080#00");
  ASSERT_TRUE(e.ok());
  EXPECT_TRUE(e->frame.error);
  EXPECT_EQ(e->frame.id, 0x80u);
  core::Result<CandumpRecord> dots = ParseCandumpLine("(2.0) can0 123#11.22.33");
  ASSERT_TRUE(dots.ok());
  EXPECT_EQ(dots->frame.len, 3);
}

TEST(CandumpLogTest, MalformedLinesAreCountedNotFatal) {
  const CandumpLog log = ParseCandumpLog(
      "# comment\n(1.0) can0 123#11\n(x) can0 123#11\n(1.0) can0 1234#11\n(1.0) can0 123#112\n"
      "(1.0) can0 123#112233445566778899\n(1.0) can0 9FFFFFFF#00\n\n(2.0) can0 7FF#\n");
  EXPECT_EQ(log.stats.records, 2u);
  EXPECT_EQ(log.stats.malformed, 5u);
  EXPECT_EQ(log.stats.ignored, 2u);
  ASSERT_FALSE(log.errors.empty());
  EXPECT_NE(log.errors.front().find("line 3"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::drivers::can
