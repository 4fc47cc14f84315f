#include "vehicle_agent/localization/likelihood_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "tests/vehicle_agent/test_grids.h"
#include "vehicle_agent/localization/scan_endpoints.h"

namespace fleetmap::vehicle_agent {
namespace {

using test_grids::PerfectScan;
using test_grids::Room;

TEST(LikelihoodFieldTest, MeasuresDistanceToTheWallsSurfaceOnBothSides) {
  // Walls 4 cells (20 cm) thick: the inner face of the left wall is at x = 0.2 m.
  LikelihoodField field{LikelihoodFieldOptions()};
  field.SetMap(Room(4));
  EXPECT_NEAR(field.DistanceAt({0.225, 3.0}), 0.025, 1e-6);  // first free cell
  EXPECT_NEAR(field.DistanceAt({0.175, 3.0}), 0.025, 1e-6);  // the wall's surface cell
  EXPECT_NEAR(field.DistanceAt({1.225, 3.0}), 1.025, 1e-6);
  EXPECT_NEAR(field.DistanceAt({0.075, 3.0}), 0.125, 1e-6);  // deep inside: penalised too
  EXPECT_NEAR(field.DistanceAt({5.0, 3.0}), 2.0, 1e-6);      // clamped to max_distance_m
  EXPECT_NEAR(field.DistanceAt({-5.0, 3.0}), 2.0, 1e-6);     // off the map
  EXPECT_GT(field.LogLikelihoodAt({0.225, 3.0}), field.LogLikelihoodAt({0.325, 3.0}));
  EXPECT_NEAR(field.LogLikelihoodAt({-5.0, 3.0}), field.LogLikelihoodAt({5.0, 3.0}), 1e-5);
}

TEST(LikelihoodFieldTest, ScoresTheTruePoseHighest) {
  const core::OccupancyGrid room = Room(3);
  const core::Pose2 truth(3.0, 2.0, 0.3);
  const core::LaserScan scan = PerfectScan(room, truth);
  LikelihoodFieldOptions o;
  o.beam_stride = 1;
  LikelihoodField field(o);
  field.SetMap(room);
  const ScanScore best = field.Score(scan, truth);
  EXPECT_EQ(best.beams_used, 360);
  // Two cells off: one cell may only move end points across a face (0.5 cells either side).
  for (const core::Pose2& off :
       {core::Pose2(0.1, 0, 0), core::Pose2(-0.1, 0, 0), core::Pose2(0, 0.1, 0),
        core::Pose2(0, -0.1, 0), core::Pose2(0, 0, 0.03), core::Pose2(0, 0, -0.03)}) {
    EXPECT_LT(field.MeanBeamLikelihood(scan, truth * off), best.mean_beam_likelihood);
  }
}

// The particle filter's batch path gives what the per-point path gives, also on a grid whose
// origin is rotated and shifted.
TEST(LikelihoodFieldTest, BatchScoringMatchesPointScoring) {
  const core::OccupancyGrid room = Room(2, core::Pose2(-1.0, 2.0, 0.4));
  const core::Pose2 mount(0.3, 0.0, 0.0);
  const core::Pose2 base = room.geometry().origin() * core::Pose2(4.0, 3.0, 1.0);
  const core::LaserScan scan = PerfectScan(room, base * mount);
  std::vector<Eigen::Vector2f> endpoints;
  const EndpointCounts counts = ScanEndpoints(scan, mount, 1000, 30.0, endpoints);
  ASSERT_EQ(counts.returns, 360);
  LikelihoodField field{LikelihoodFieldOptions()};
  field.SetMap(room);
  for (const core::Pose2& pose : {base, base * core::Pose2(0.1, -0.2, 0.05)}) {
    double expected = 0.0;
    for (const Eigen::Vector2f& e : endpoints)
      expected += field.LogLikelihoodAt(pose.Apply(e.cast<double>()));
    EXPECT_NEAR(field.LogLikelihood(endpoints, pose), expected, 1e-3 * std::abs(expected));
  }
}

TEST(LikelihoodFieldTest, SkipsNoReturnsAndCountsBadRanges) {
  const core::OccupancyGrid room = Room();
  const core::Pose2 pose(3.0, 2.0, 0.0);
  core::LaserScan scan = PerfectScan(room, pose);
  scan.ranges_m[0] = NAN;
  scan.ranges_m[1] = -2.0f;
  scan.ranges_m[2] = 0.0f;
  scan.ranges_m[3] = INFINITY;
  scan.ranges_m[4] = 45.0f;  // beyond range_max_m: no return
  LikelihoodFieldOptions o;
  o.beam_stride = 1;
  LikelihoodField field(o);
  EXPECT_TRUE(std::isnan(field.MeanBeamLikelihood(scan, pose)));  // no map yet
  field.SetMap(room);
  const ScanScore s = field.Score(scan, pose);
  EXPECT_EQ(s.beams_invalid, 3);
  EXPECT_EQ(s.beams_no_return, 2);
  EXPECT_EQ(s.beams_used, 355);
  EXPECT_TRUE(std::isfinite(s.mean_beam_likelihood));
  const std::vector<Eigen::Vector2f> far = {{1e30f, -1e30f}, {NAN, 0.0f}};
  EXPECT_TRUE(std::isfinite(field.LogLikelihood(far, pose)));
  EXPECT_TRUE(std::isfinite(field.LogLikelihoodAt({1e300, 1e300})));
}

// Every cell's distance and log p, at its centre.
std::vector<std::pair<float, float>> FieldValues(const LikelihoodField& field,
                                                 const core::GridGeometry& g) {
  std::vector<std::pair<float, float>> values;
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x) {
      const Eigen::Vector2d c = g.CellCenter({x, y});
      values.emplace_back(static_cast<float>(field.DistanceAt(c)),
                          static_cast<float>(field.LogLikelihoodAt(c)));
    }
  return values;
}

// A new map version updated around its change gives the field of the whole map rebuilt, cell
// for cell: a pallet taken away, one added beside a wall (the wall's surface cells outside the
// changed window change too) and one at the grid's corner.
TEST(LikelihoodFieldTest, AnUpdateAroundTheChangeGivesTheWholeMapsField) {
  for (double max_distance_m : {0.4, 2.0}) {
    LikelihoodFieldOptions o;
    o.max_distance_m = max_distance_m;
    core::OccupancyGrid before = Room(2, core::Pose2(1.0, -2.0, 0.3));
    test_grids::AddBox(before, 3.0, 2.0, 4.2, 2.8);
    core::OccupancyGrid after = before;
    for (int y = 40; y < 56; ++y)
      for (int x = 60; x < 84; ++x) after.SetState({x, y}, core::CellState::kFree);
    for (int y = 2; y < 20; ++y)
      for (int x = 150; x < 170; ++x) after.SetState({x, y}, core::CellState::kOccupied);
    after.SetState({199, 119}, core::CellState::kFree);
    LikelihoodField updated(o), rebuilt(o);
    updated.SetMap(before);
    const auto values_before = FieldValues(updated, before.geometry());
    updated.UpdateMap(after, {60, 2, 140, 118});
    rebuilt.SetMap(after);
    const auto want = FieldValues(rebuilt, after.geometry());
    ASSERT_NE(values_before, want) << "the change moves nothing: the test tests nothing";
    EXPECT_EQ(FieldValues(updated, after.geometry()), want) << max_distance_m;
  }
}

TEST(LikelihoodFieldTest, AnUpdateOfAnotherGeometryRebuilds) {
  LikelihoodField updated{LikelihoodFieldOptions()}, rebuilt{LikelihoodFieldOptions()};
  updated.SetMap(Room(2));
  const core::OccupancyGrid moved = Room(3, core::Pose2(0.5, 0.0, 0.0));
  updated.UpdateMap(moved, {0, 0, 1, 1});
  rebuilt.SetMap(moved);
  EXPECT_EQ(FieldValues(updated, moved.geometry()), FieldValues(rebuilt, moved.geometry()));
}

TEST(LikelihoodFieldTest, ValidateNamesTheBadField) {
  LikelihoodFieldOptions o;
  o.max_distance_m = 0.0;
  EXPECT_NE(o.Validate().message().find("LikelihoodFieldOptions.max_distance_m"),
            std::string::npos);
  o = LikelihoodFieldOptions();
  o.z_hit = -1.0;
  EXPECT_NE(o.Validate().message().find("z_hit"), std::string::npos);
  EXPECT_TRUE(LikelihoodFieldOptions().Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
