// core/command_line.h: every program's flags read alike.
#include "core/command_line.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fleetmap::core {
namespace {

// Runs ParseCommandLine on `args` (the program's name first) for an app with one number.
struct Parsed {
  std::optional<int> exit_status;
  double period_s = 10.0;
  std::string out, err;
};

Parsed Parse(std::vector<std::string> args) {
  Parsed p;
  CLI::App app("Test program.", "fleetmap-test");
  AddVersionFlag(app);
  app.add_option("--period", p.period_s, "seconds")->check(Finite())->capture_default_str();
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  p.exit_status = ParseCommandLine(app, static_cast<int>(argv.size()), argv.data());
  p.out = testing::internal::GetCapturedStdout();
  p.err = testing::internal::GetCapturedStderr();
  return p;
}

TEST(CommandLineTest, AGoodLineGoesOnWithItsValues) {
  const Parsed p = Parse({"fleetmap-test", "--period", "2.5"});
  EXPECT_FALSE(p.exit_status.has_value());
  EXPECT_DOUBLE_EQ(p.period_s, 2.5);
}

TEST(CommandLineTest, HelpAndVersionEndTheProgramWithZero) {
  const Parsed help = Parse({"fleetmap-test", "--help"});
  EXPECT_EQ(help.exit_status, 0);
  EXPECT_NE(help.out.find("Usage: fleetmap-test"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--period"), std::string::npos) << help.out;
  const Parsed version = Parse({"fleetmap-test", "--version"});
  EXPECT_EQ(version.exit_status, 0);
  EXPECT_EQ(version.out, std::string("fleetmap-test ") + kFleetmapVersion + "\n");
}

TEST(CommandLineTest, ABadValueIsAUsageErrorThatNamesTheFlag) {
  for (const char* bad : {"nan", "inf", "60s", ""}) {
    const Parsed p = Parse({"fleetmap-test", "--period", bad});
    EXPECT_EQ(p.exit_status, 2) << bad;
    EXPECT_NE(p.err.find("fleetmap-test: "), std::string::npos) << p.err;
    EXPECT_NE(p.err.find("--period"), std::string::npos) << bad << ": " << p.err;
    EXPECT_DOUBLE_EQ(p.period_s, 10.0) << bad;
  }
}

TEST(CommandLineTest, PositiveRefusesZeroNegativeAndNotFinite) {
  for (const char* bad : {"0", "-1", "nan", "inf", "1s"}) {
    std::string text = bad;
    EXPECT_FALSE(Positive()(text).empty()) << bad;
  }
  std::string good = "0.05";
  EXPECT_EQ(Positive()(good), "");
}

TEST(CommandLineTest, NotNegativeTakesZeroAndRefusesBelowZeroAndNotFinite) {
  for (const char* bad : {"-0.5", "-1", "nan", "inf", "1s"}) {
    std::string text = bad;
    EXPECT_FALSE(NotNegative()(text).empty()) << bad;
  }
  for (const char* good : {"0", "12.5"}) {
    std::string text = good;
    EXPECT_EQ(NotNegative()(text), "") << good;
  }
}

TEST(CommandLineTest, WholeNumberTakesDigitsOnly) {
  for (const char* bad : {"-2", "2.5", "1e3", "", "x"}) {
    std::string text = bad;
    EXPECT_FALSE(WholeNumber()(text).empty()) << bad;
  }
  std::string good = "42";
  EXPECT_EQ(WholeNumber()(good), "");
}

TEST(CommandLineTest, AnUnknownFlagIsAUsageError) {
  const Parsed p = Parse({"fleetmap-test", "--perod", "2"});
  EXPECT_EQ(p.exit_status, 2);
  EXPECT_NE(p.err.find("--perod"), std::string::npos) << p.err;
}

}  // namespace
}  // namespace fleetmap::core
