// edge/cause_log.h: bad input is logged once per cause, and the set of causes is bounded.
#include "edge/cause_log.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "edge/link.h"

namespace fleetmap::edge {
namespace {

struct Kept {
  std::vector<std::pair<LogLevel, std::string>> lines;
  LogSink Sink() {
    return [this](LogLevel level, const std::string& line) { lines.emplace_back(level, line); };
  }
};

TEST(CauseLogTest, EachCauseIsLoggedOnceAsAWarning) {
  Kept kept;
  CauseLog log(kept.Sink());
  EXPECT_TRUE(log.Once("MAP_DELTA: malformed", "MAP_DELTA from v1: malformed"));
  EXPECT_FALSE(log.Once("MAP_DELTA: malformed", "MAP_DELTA from v2: malformed"));
  EXPECT_TRUE(log.Once("MAP_REQUEST: malformed", "MAP_REQUEST: malformed"));
  ASSERT_EQ(kept.lines.size(), 2u);
  EXPECT_EQ(kept.lines[0].first, LogLevel::kWarning);
  EXPECT_EQ(kept.lines[0].second.rfind("MAP_DELTA from v1: malformed (logged once", 0), 0u)
      << kept.lines[0].second;
}

TEST(CauseLogTest, InfoAndWarningPassThroughAtTheirLevel) {
  Kept kept;
  CauseLog log(kept.Sink());
  log.Info("started");
  log.Warning("late");
  ASSERT_EQ(kept.lines.size(), 2u);
  EXPECT_EQ(kept.lines[0], std::make_pair(LogLevel::kInfo, std::string("started")));
  EXPECT_EQ(kept.lines[1], std::make_pair(LogLevel::kWarning, std::string("late")));
}

TEST(CauseLogTest, ASenderInventingCausesCannotGrowTheSetWithoutEnd) {
  Kept kept;
  CauseLog log(kept.Sink());
  int logged = 0;
  for (int i = 0; i < 10000; ++i) logged += log.Once("cause " + std::to_string(i), "bad") ? 1 : 0;
  EXPECT_EQ(logged, 256);
  EXPECT_EQ(kept.lines.size(), 256u);
}

TEST(CauseLogTest, WithoutASinkNothingIsWrittenAndCausesAreStillKept) {
  CauseLog log(nullptr);
  log.Info("nowhere");
  EXPECT_TRUE(log.Once("c", "line"));
  EXPECT_FALSE(log.Once("c", "line"));
}

TEST(LinkTest, EveryLinkHasItsName) {
  EXPECT_STREQ(LinkName(Link::kSensor), "sensor");
  EXPECT_STREQ(LinkName(Link::kUplink), "uplink");
  EXPECT_STREQ(LinkName(Link::kDownlink), "downlink");
}

}  // namespace
}  // namespace fleetmap::edge
