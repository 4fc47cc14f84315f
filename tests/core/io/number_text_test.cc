#include "core/io/number_text.h"

#include <gtest/gtest.h>

namespace fleetmap::core {
namespace {

TEST(NumberTextTest, ReadsWholeNumbersAndRefusesSignsAndTrailingText) {
  EXPECT_EQ(*ParseCount("100", "--count"), 100u);
  EXPECT_EQ(*ParseCount("0", "--count"), 0u);
  for (const char* bad : {"-5", "+5", "", "5x", "1e3", " 5", "99999999999999999999999"})
    EXPECT_FALSE(ParseCount(bad, "--count").ok()) << bad;
  EXPECT_FALSE(ParseCount("11", "--vehicle", 10).ok());
  const auto error = ParseCount("-5", "--count");
  EXPECT_NE(error.status().ToString().find("--count"), std::string::npos);
}

TEST(NumberTextTest, ReadsFiniteNumbersOnly) {
  EXPECT_DOUBLE_EQ(*ParseNumber("2.5", "--speed"), 2.5);
  EXPECT_DOUBLE_EQ(*ParseNumber("-1e-3", "--speed"), -1e-3);
  for (const char* bad : {"", "2x", "nan", "inf", "1e999", "0x"})
    EXPECT_FALSE(ParseNumber(bad, "--speed").ok()) << bad;
}

}  // namespace
}  // namespace fleetmap::core
