// Inputs on which fuzz/candump_fuzz.cc found the candump reader misbehaving; the fuzzer's own
// input is in tests/data/fuzz/candump/. Fixed in drivers/can/candump_log.cc.
#include <gtest/gtest.h>

#include "core/io/file_io.h"
#include "drivers/can/candump_log.h"

namespace fleetmap::drivers::can {
namespace {

// A stamp of 19 integer digits parsed, and FormatCandumpLine wrote it back as a line the
// parser refused (26 characters); from 1e19 s on it overflowed the conversion to long long.
TEST(CandumpFuzzRegressionTest, AbsurdTimestampsAreRefused) {
  auto text = core::ReadFileBytes(
      FLEETMAP_SOURCE_DIR "/tests/data/fuzz/candump/nineteen_digit_timestamp", 1 << 20);
  ASSERT_TRUE(text.ok());
  const CandumpLog log = ParseCandumpLog(*text);
  EXPECT_GT(log.stats.malformed, 0u);
  for (const CandumpRecord& r : log.records) {
    auto back = ParseCandumpLine(FormatCandumpLine(r));
    ASSERT_TRUE(back.ok()) << FormatCandumpLine(r);
    EXPECT_EQ(back->frame.id, r.frame.id);
  }
  EXPECT_FALSE(ParseCandumpLine("(1649249890000730936) can0 243#").ok());
  EXPECT_FALSE(ParseCandumpLine("(99999999999999999999.5) can0 243#").ok());
  auto latest = ParseCandumpLine("(999999999999.5) can0 243#00");
  ASSERT_TRUE(latest.ok());
  EXPECT_TRUE(ParseCandumpLine(FormatCandumpLine(*latest)).ok());
}

}  // namespace
}  // namespace fleetmap::drivers::can
