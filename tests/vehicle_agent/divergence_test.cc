#include "vehicle_agent/divergence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace fleetmap::vehicle_agent {
namespace {

constexpr double kScan_s = 0.04;  // 25 Hz

DivergenceOptions Paper() {
  DivergenceOptions o;
  o.rule = DivergenceRule::kPaper;
  o.warm_up = false;
  o.alpha_slow = 0.01;
  o.alpha_fast = 0.5;
  return o;
}

TEST(DivergenceTest, FollowsThePapersEquationsExactly) {
  DivergenceDetector detector(Paper());
  const std::vector<double> w_avg = {2.0, 2.0, 1.0, 1.0, 4.0, 0.5};
  double w_slow = 2.0, w_fast = 2.0;  // W(0) = the first W_avg
  for (size_t t = 0; t < w_avg.size(); ++t) {
    const DivergenceSample s = detector.Update(t * kScan_s, w_avg[t], 0.0);
    EXPECT_DOUBLE_EQ(s.w_slow, w_slow) << t;
    EXPECT_DOUBLE_EQ(s.w_fast, w_fast) << t;
    EXPECT_DOUBLE_EQ(s.d, std::max(0.0, 1.0 - w_fast / w_slow)) << t;  // eq. (4)
    w_slow += 0.01 * (w_avg[t] - w_slow);                              // eq. (2)
    w_fast += 0.5 * (w_avg[t] - w_fast);                               // eq. (3)
  }
}

TEST(DivergenceTest, ThePapersRuleStartsAtAnyDivergenceAndStopsAtNone) {
  DivergenceDetector detector(Paper());
  detector.Update(0.00, 2.0, 0.0);
  detector.Update(0.04, 1.0, 0.0);  // enters W(t+1): d > 0 from the next sample
  const DivergenceSample up = detector.Update(0.08, 1.0, 0.0);
  EXPECT_GT(up.d, 0.0);
  EXPECT_TRUE(up.started);
  EXPECT_TRUE(up.building);
  DivergenceSample s;
  for (int i = 3; i < 20 && !s.stopped; ++i) s = detector.Update(i * kScan_s, 3.0, 0.0);
  EXPECT_TRUE(s.stopped);
  EXPECT_EQ(s.d, 0.0);
  EXPECT_FALSE(detector.building());
  EXPECT_EQ(detector.stats().starts, 1);
  EXPECT_EQ(detector.stats().stops, 1);
}

TEST(DivergenceTest, WarmUpStartsFromTheRunningMean) {
  DivergenceOptions o;
  o.warm_up = true;
  DivergenceDetector detector(o);
  detector.Update(0.00, 1.0, 0.0);
  detector.Update(0.04, 2.0, 0.0);
  const DivergenceSample s = detector.Update(0.08, 3.0, 0.0);
  EXPECT_DOUBLE_EQ(s.w_slow, 1.5);  // the mean of the first two, not 1.0 + 0.001 * 1.0
  EXPECT_DOUBLE_EQ(s.w_fast, 1.5);
  // After 1 / alpha_fast samples W_fast follows eq. (3) again; W_slow is still the mean.
  for (int i = 3; i < 40; ++i) detector.Update(i * kScan_s, 3.0, 0.0);
  const DivergenceSample later = detector.Update(40 * kScan_s, 0.0, 0.0);
  const double mean = (1.0 + 2.0 + 3.0 * 38) / 40.0;
  EXPECT_NEAR(later.w_slow, mean, 1e-12);
  const DivergenceSample next = detector.Update(41 * kScan_s, 0.0, 0.0);
  EXPECT_NEAR(next.w_fast, later.w_fast * (1.0 - o.alpha_fast), 1e-12);
}

// Hysteresis: start above 0.1, hold at least min_duration_s, stop below 0.05.
TEST(DivergenceTest, HysteresisNeedsAClearDivergenceAndHoldsTheMap) {
  DivergenceOptions o;
  o.warm_up = false;
  o.map_at_start = false;  // the rule alone (below: the map at start-up)
  o.start_above = 0.1;     // the mechanism, at thresholds apart from the defaults' 0.05 / 0.025
  o.stop_below = 0.05;
  o.min_duration_s = 2.0;
  DivergenceDetector detector(o);
  double t = 0.0;
  auto feed = [&](double w, int n) {
    DivergenceSample s;
    for (int i = 0; i < n; ++i, t += kScan_s) {
      s = detector.Update(t, w, 0.0);
      if (s.started || s.stopped) return s;
    }
    return s;
  };
  feed(1.0, 50);
  EXPECT_FALSE(feed(0.95, 100).started);  // d about 0.05: below start_above
  const DivergenceSample start = feed(0.7, 100);
  ASSERT_TRUE(start.started);
  EXPECT_GT(start.d, o.start_above);
  const double started_s = start.stamp_s;
  const DivergenceSample stop = feed(1.1, 500);  // d falls to 0 at once
  ASSERT_TRUE(stop.stopped);
  EXPECT_NEAR(stop.stamp_s - started_s, o.min_duration_s, 2 * kScan_s);
}

// Whatever is in view from the first scan on is part of the past d compares with: the first
// sample opens a map that lasts min_duration_s, and after Reset the first localized one.
TEST(DivergenceTest, TheFirstSampleOpensAMapThatLastsTheMinimumDuration) {
  for (const bool at_start : {true, false}) {
    DivergenceOptions o;
    o.map_at_start = at_start;
    o.min_duration_s = 2.0;
    DivergenceDetector detector(o);
    const DivergenceSample first = detector.Update(0.0, 1.0, 0.0);
    EXPECT_EQ(first.started, at_start);
    EXPECT_EQ(first.building, at_start);
    double t = 0.0, stopped_s = -1.0;
    for (int i = 1; i < 150; ++i) {  // 6 s of scans that fit as well as the first
      t = i * kScan_s;
      if (detector.Update(t, 1.0, 0.0).stopped) stopped_s = t;
    }
    EXPECT_EQ(detector.stats().starts, at_start ? 1 : 0);
    if (at_start) {
      EXPECT_NEAR(stopped_s, o.min_duration_s, 2 * kScan_s);
    }
    // After a reset (a global re-localization) it waits until the vehicle is localized.
    detector.Reset();
    EXPECT_FALSE(detector.Update(t + kScan_s, 1.0, 0.0, /*localized=*/false).started);
    EXPECT_FALSE(detector.Update(t + 2 * kScan_s, 1.0, 0.0, false).building);
    EXPECT_EQ(detector.Update(t + 3 * kScan_s, 1.0, 0.0, true).started, at_start);
    EXPECT_FALSE(detector.Update(t + 4 * kScan_s, 1.0, 0.0, true).started);
  }
}

TEST(DivergenceTest, HysteresisSplitsAVeryLongChangeAtMaxDuration) {
  DivergenceOptions o;
  o.warm_up = false;
  o.alpha_slow = 0.0;  // the long-term average never absorbs the change
  o.map_at_start = false;
  o.min_duration_s = 2.0;  // Validate(): at most max_duration_s (the default is 20 s)
  o.max_duration_s = 4.0;
  ASSERT_TRUE(o.Validate().ok());
  DivergenceDetector detector(o);
  double t = 0.0;
  for (; t < 1.0; t += kScan_s) detector.Update(t, 1.0, 0.0);
  for (; t < 10.0; t += kScan_s) detector.Update(t, 0.5, 0.0);
  EXPECT_EQ(detector.stats().stops, 2);
  EXPECT_EQ(detector.stats().starts, 3);
  EXPECT_TRUE(detector.building());
}

// The scan fits the map worse while turning (say, a scan skewed by the rotation): frozen
// averages ignore it; without the freeze it opens a temporary map.
TEST(DivergenceTest, DoesNotUpdateWhileRotating) {
  for (const bool freeze : {true, false}) {
    DivergenceOptions o;
    o.rotation_freeze_radps = freeze ? 0.1 : 1e9;
    o.map_at_start = false;
    DivergenceDetector detector(o);
    double t = 0.0;
    for (; t < 5.0; t += kScan_s) detector.Update(t, 1.0, 0.0);
    const DivergenceSample before = detector.Update(t, 1.0, 0.0);
    DivergenceSample during;
    for (t += kScan_s; t < 8.0; t += kScan_s) during = detector.Update(t, 0.5, 0.5);
    EXPECT_EQ(during.rotating, freeze);
    if (freeze) {
      EXPECT_EQ(during.w_fast, before.w_fast);
      EXPECT_EQ(during.w_slow, before.w_slow);
      EXPECT_EQ(detector.stats().starts, 0);
      EXPECT_GT(detector.stats().rotating, 50);
    } else {
      EXPECT_EQ(detector.stats().starts, 1);
    }
  }
}

TEST(DivergenceTest, AClockSetBackIsANewReferenceAndKeepsTheMapsDuration) {
  DivergenceOptions options;
  options.min_duration_s = 2.0;
  options.map_at_start = false;
  DivergenceDetector detector{options};
  double t = 100.0;
  for (int i = 0; i < 100; ++i, t += 0.04) detector.Update(t, 1.0, 0.0);
  bool started = false;  // a change: building
  for (int i = 0; i < 10 && !started; ++i, t += 0.04)
    started = detector.Update(t, 0.01, 0.0).started;
  ASSERT_TRUE(started);
  // The clock is set back an hour one second into the map: accepted, not out of order ...
  for (int i = 0; i < 25; ++i, t += 0.04) ASSERT_TRUE(detector.Update(t, 0.01, 0.0).accepted);
  t -= 3600.0;
  EXPECT_TRUE(detector.Update(t, 0.01, 0.0).accepted);
  EXPECT_EQ(detector.stats().dropped_out_of_order, 0);
  // ... and the map's duration goes on: with no divergence it stops after min_duration_s.
  bool stopped = false;
  for (int i = 0; i < 100 && !stopped; ++i) {
    t += 0.04;
    stopped = detector.Update(t, 1.0, 0.0).stopped;
  }
  EXPECT_TRUE(stopped);
}

TEST(DivergenceTest, DropsAndCountsBadInput) {
  DivergenceDetector detector{DivergenceOptions()};
  detector.Update(1.0, 1.0, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(detector.Update(1.04, nan, 0.0).accepted);
  EXPECT_FALSE(detector.Update(1.08, inf, 0.0).accepted);
  EXPECT_FALSE(detector.Update(1.12, -0.5, 0.0).accepted);
  EXPECT_FALSE(detector.Update(nan, 1.0, 0.0).accepted);
  EXPECT_FALSE(detector.Update(1.16, 1.0, nan).accepted);
  EXPECT_EQ(detector.stats().dropped_invalid, 5);
  EXPECT_FALSE(detector.Update(0.5, 0.1, 0.0).accepted);  // back in time
  EXPECT_EQ(detector.stats().dropped_out_of_order, 1);
  const DivergenceSample s = detector.Update(1.2, 1.0, inf);  // spinning: frozen, not bad
  EXPECT_TRUE(s.accepted);
  EXPECT_TRUE(s.rotating);
  EXPECT_EQ(s.w_slow, 1.0);
  EXPECT_EQ(s.d, 0.0);
  EXPECT_EQ(detector.stats().samples, 2);
  EXPECT_TRUE(detector.Update(1.24, 0.0, 0.0).accepted);  // W_avg = 0 is a valid reading
}

TEST(DivergenceTest, ValidateNamesTheBadField) {
  DivergenceOptions o;
  o.alpha_slow = 0.5;
  EXPECT_NE(o.Validate().message().find("alpha_slow"), std::string::npos);
  o = DivergenceOptions();
  o.stop_below = 0.3;
  EXPECT_NE(o.Validate().message().find("start_above"), std::string::npos);
  o = DivergenceOptions();
  o.max_duration_s = 1.0;
  EXPECT_NE(o.Validate().message().find("max_duration_s"), std::string::npos);
  o = DivergenceOptions();
  o.rotation_freeze_radps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(o.Validate().message().find("rotation_freeze_radps"), std::string::npos);
  EXPECT_TRUE(DivergenceOptions().Validate().ok());
  EXPECT_TRUE(Paper().Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
