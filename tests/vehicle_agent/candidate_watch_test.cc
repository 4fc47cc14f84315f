#include "vehicle_agent/candidate_watch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace fleetmap::vehicle_agent {
namespace {

// 10 x 10 m at 5 cm; the scanner at (1, 5) looking along +x.
const core::GridGeometry kGrid(0.05, 200, 200);
const core::Pose2 kScanner(1.0, 5.0, 0.0);

// A 270 deg scan in which every beam returns from `far_m`.
core::LaserScan Scan(double stamp_s, float far_m = 8.0f) {
  core::LaserScan s;
  s.stamp_s = stamp_s;
  s.angle_min_rad = -0.75 * M_PI;
  s.angle_increment_rad = M_PI / 360.0;
  s.range_min_m = 0.05;
  s.range_max_m = 30.0;
  s.ranges_m.assign(541, far_m);
  return s;
}

// The beams whose bearing lies within `half_width_rad` of `bearing_rad` return from `range_m`.
void Return(core::LaserScan& s, double bearing_rad, double half_width_rad, float range_m) {
  for (size_t i = 0; i < s.size(); ++i)
    if (std::abs(s.angle(i) - bearing_rad) <= half_width_rad) s.ranges_m[i] = range_m;
}

// A candidate 3 m ahead of the scanner.
int64_t Ahead() { return kGrid.Index(kGrid.WorldToCell({4.0, 5.0})); }

TEST(CandidateWatchTest, ACandidateBeamsPassThroughIsReportedOnceAfterEnoughScans) {
  CandidateWatchOptions o;
  CandidateWatch watch(kGrid, o);
  watch.SetCandidates({Ahead()});
  for (int k = 0; k < o.min_free_scans - 1; ++k) watch.Observe(Scan(10.0 + 0.04 * k), kScanner);
  EXPECT_TRUE(watch.TakeSeenFree().cells.empty());
  watch.Observe(Scan(10.2), kScanner);
  const CandidatesSeenFree free = watch.TakeSeenFree();
  ASSERT_EQ(free.cells, std::vector<int64_t>{Ahead()});
  EXPECT_DOUBLE_EQ(free.first_pass_s, 10.0);
  EXPECT_DOUBLE_EQ(free.last_pass_s, 10.2);
  for (int k = 0; k < 10; ++k) watch.Observe(Scan(11.0 + 0.04 * k), kScanner);
  EXPECT_TRUE(watch.TakeSeenFree().cells.empty());  // once, not again
}

TEST(CandidateWatchTest, ACandidateStillThereIsNeverReported) {
  CandidateWatch watch(kGrid, {});
  watch.SetCandidates({Ahead()});
  for (int k = 0; k < 20; ++k) {
    core::LaserScan s = Scan(0.04 * k);
    Return(s, 0.0, 0.1, 3.0f);  // a face at the candidate
    watch.Observe(s, kScanner);
  }
  EXPECT_TRUE(watch.TakeSeenFree().cells.empty());
}

// A beam that grazes an object beside the cell: the beam nearest the cell's centre passes,
// the next one ends on the object at the cell's range. The cell may hold the object's edge.
TEST(CandidateWatchTest, ACellBesideWhichABeamEndsIsNotReported) {
  CandidateWatch watch(kGrid, {});
  watch.SetCandidates({Ahead()});
  const Eigen::Vector2d centre = kGrid.CellCenter(kGrid.WorldToCell({4.0, 5.0}));
  const double bearing = std::atan2(centre.y() - 5.0, centre.x() - 1.0);
  const double increment = M_PI / 360.0;
  const float range = static_cast<float>((centre - Eigen::Vector2d(1.0, 5.0)).norm());
  for (int k = 0; k < 20; ++k) {
    core::LaserScan s = Scan(0.04 * k);
    Return(s, bearing + 1.1 * increment, 0.5 * increment, range);
    watch.Observe(s, kScanner);
  }
  EXPECT_TRUE(watch.TakeSeenFree().cells.empty());
}

TEST(CandidateWatchTest, AHitStartsTheCountAgain) {
  CandidateWatchOptions o;
  CandidateWatch watch(kGrid, o);
  watch.SetCandidates({Ahead()});
  for (int k = 0; k < 2 * o.min_free_scans - 1; ++k) {
    core::LaserScan s = Scan(0.04 * k);
    if (k == o.min_free_scans - 1) Return(s, 0.0, 0.1, 3.05f);  // a person steps in once
    watch.Observe(s, kScanner);
  }
  EXPECT_TRUE(watch.TakeSeenFree().cells.empty());
  watch.Observe(Scan(1.0), kScanner);
  EXPECT_EQ(watch.TakeSeenFree().cells.size(), 1u);
}

TEST(CandidateWatchTest, SomethingInFrontOrNoUsableReturnSaysNothing) {
  CandidateWatch watch(kGrid, {});
  watch.SetCandidates({Ahead()});
  for (int k = 0; k < 20; ++k) {
    core::LaserScan s = Scan(0.04 * k);
    Return(s, 0.0, 0.1, k % 2 ? 1.5f : std::numeric_limits<float>::quiet_NaN());
    watch.Observe(s, kScanner);
  }
  EXPECT_TRUE(watch.TakeSeenFree().cells.empty());
}

TEST(CandidateWatchTest, NoReturnWithinRangeIsAPassAndBehindTheScannerIsUnseen) {
  CandidateWatch watch(kGrid, {});
  const int64_t behind = kGrid.Index(kGrid.WorldToCell({0.2, 5.0}));  // outside the 270 deg
  watch.SetCandidates({Ahead(), behind});
  for (int k = 0; k < 10; ++k)
    watch.Observe(Scan(0.04 * k, std::numeric_limits<float>::infinity()), kScanner);
  EXPECT_EQ(watch.TakeSeenFree().cells, std::vector<int64_t>{Ahead()});
}

TEST(CandidateWatchTest, ACellNoLongerACandidateIsNotReportedAndOutsideCellsAreIgnored) {
  CandidateWatch watch(kGrid, {});
  watch.SetCandidates({Ahead(), -1, kGrid.num_cells()});
  EXPECT_EQ(watch.num_candidates(), 1u);
  for (int k = 0; k < 10; ++k) watch.Observe(Scan(0.04 * k), kScanner);
  watch.SetCandidates({});  // confirmed or dropped by a merge meanwhile
  EXPECT_TRUE(watch.TakeSeenFree().cells.empty());
}

// Scans every 0.04 s from `from_s` to `to_s`, a face at the candidate where `there` says so.
template <typename There>
void Watch(CandidateWatch& watch, double from_s, double to_s, There there) {
  for (double t = from_s; t < to_s - 1e-9; t += 0.04) {
    core::LaserScan s = Scan(t);
    if (there(t)) Return(s, 0.0, 0.1, 3.0f);
    watch.Observe(s, kScanner);
  }
}

// A pallet this vehicle's beams end at for 12 s: it is held from the first of them, though
// the aggregator made it a candidate only 5 s later, and reported once after 10 s.
TEST(CandidateWatchTest, ACandidateHeldLongEnoughIsReportedFromWhenBeamsBeganToEndThere) {
  CandidateWatchOptions o;
  o.report_held_s = 10.0;
  CandidateWatch watch(kGrid, o);
  Watch(watch, 0.0, 5.0, [](double) { return true; });
  watch.SetCandidates({Ahead()});
  Watch(watch, 5.0, 9.9, [](double) { return true; });
  EXPECT_TRUE(watch.TakeHeld().cells.empty());
  Watch(watch, 9.9, 12.0, [](double) { return true; });
  const CandidatesHeld held = watch.TakeHeld();
  ASSERT_EQ(held.cells, std::vector<int64_t>{Ahead()});
  EXPECT_NEAR(held.since_s[0], 0.0, 1e-9);
  EXPECT_GE(held.until_s[0], o.report_held_s);
  Watch(watch, 12.0, 14.0, [](double) { return true; });
  EXPECT_TRUE(watch.TakeHeld().cells.empty());  // once
}

// Beams that passed through the place (a forklift that left and came back), or none that
// ended there for longer than hold_gap_s (the vehicle looked elsewhere), start the hold again.
TEST(CandidateWatchTest, APassOrAPauseStartsTheHoldAgain) {
  CandidateWatchOptions o;
  o.report_held_s = 10.0;
  CandidateWatch passed(kGrid, o);
  passed.SetCandidates({Ahead()});
  Watch(passed, 0.0, 16.0, [](double t) { return t < 8.0 || t >= 8.5; });
  EXPECT_TRUE(passed.TakeHeld().cells.empty());
  CandidateWatch paused(kGrid, o);
  paused.SetCandidates({Ahead()});
  Watch(paused, 0.0, 6.0, [](double) { return true; });
  Watch(paused, 8.0, 16.0, [](double) { return true; });  // no scans from 6 to 8 s
  EXPECT_TRUE(paused.TakeHeld().cells.empty());
  Watch(paused, 16.0, 18.2, [](double) { return true; });
  const CandidatesHeld held = paused.TakeHeld();
  ASSERT_EQ(held.cells.size(), 1u);
  EXPECT_NEAR(held.since_s[0], 8.0, 0.05);
}

TEST(CandidateWatchTest, HoldsAreNotReportedByDefault) {
  CandidateWatch watch(kGrid, {});
  watch.SetCandidates({Ahead()});
  Watch(watch, 0.0, 30.0, [](double) { return true; });
  EXPECT_TRUE(watch.TakeHeld().cells.empty());
}

TEST(CandidateWatchTest, ValidateNamesTheBadField) {
  CandidateWatchOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.min_free_scans = 0;
  EXPECT_NE(o.Validate().ToString().find("min_free_scans"), std::string::npos);
  o = {};
  o.hold_gap_s = 0;
  EXPECT_NE(o.Validate().ToString().find("hold_gap_s"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
