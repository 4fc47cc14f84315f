#include "vehicle_agent/localization/beam_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/vehicle_agent/test_grids.h"
#include "vehicle_agent/localization/likelihood_field.h"

namespace fleetmap::vehicle_agent {
namespace {

using test_grids::AddBox;
using test_grids::PerfectScan;
using test_grids::Room;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(BeamModelTest, ProbabilityHasTheBooksShape) {
  const BeamModelOptions o;
  const double hit = BeamProbability(o, 5.0, 5.0, 30.0);
  // The truncated Gaussian at its peak, plus the short and random floors.
  EXPECT_NEAR(hit,
              o.z_hit / (o.sigma_hit_m * std::sqrt(2 * M_PI)) +
                  o.z_short * o.lambda_short_per_m * std::exp(-0.5) / (1 - std::exp(-0.5)) +
                  o.z_rand / 30.0,
              1e-9);
  EXPECT_GT(hit, BeamProbability(o, 5.1, 5.0, 30.0));
  // Short of the surface (an unexpected obstacle) beats beyond it (should have been stopped).
  EXPECT_GT(BeamProbability(o, 3.0, 5.0, 30.0), BeamProbability(o, 7.0, 5.0, 30.0));
  // Far beyond the surface: only the random floor.
  EXPECT_NEAR(BeamProbability(o, 20.0, 5.0, 30.0), o.z_rand / 30.0, 1e-12);
  // No return: likely when nothing is in reach, unlikely in front of a wall.
  EXPECT_GT(BeamProbability(o, INFINITY, INFINITY, 30.0), hit);
  EXPECT_NEAR(BeamProbability(o, INFINITY, 5.0, 30.0), o.z_max, 1e-12);
}

TEST(BeamModelTest, ScoresTheTruePoseHighest) {
  const core::OccupancyGrid room = Room();
  const core::Pose2 truth(3.0, 2.0, 0.3);
  const core::LaserScan scan = PerfectScan(room, truth);
  BeamModelOptions o;
  o.beam_stride = 1;
  const auto model = MakeBeamModel(o);
  model->SetMap(room);
  const ScanScore best = model->Score(scan, truth);
  EXPECT_EQ(best.beams_used, 360);
  EXPECT_EQ(best.beams_invalid, 0);
  EXPECT_NEAR(best.log_likelihood / best.beams_used, std::log(best.mean_beam_likelihood), 1e-12);
  for (const core::Pose2& off :
       {core::Pose2(0.1, 0, 0), core::Pose2(0, -0.1, 0), core::Pose2(0, 0, 0.05)}) {
    EXPECT_LT(model->MeanBeamLikelihood(scan, truth * off), best.mean_beam_likelihood);
  }
}

TEST(BeamModelTest, SeesARemovedObstacleTheLikelihoodFieldDoesNot) {
  core::OccupancyGrid map_with_box = Room();
  AddBox(map_with_box, 6.0, 1.5, 7.0, 2.5);  // mapped, then taken away
  const core::Pose2 scanner(3.0, 2.0, 0.0);
  const core::LaserScan scan = PerfectScan(Room(), scanner);  // the world has no box
  const auto beam = MakeBeamModel(BeamModelOptions());
  const auto field = MakeLikelihoodField(LikelihoodFieldOptions());
  auto ratio = [&](ScanLikelihood& model) {
    model.SetMap(Room());
    const double fits = model.MeanBeamLikelihood(scan, scanner);
    model.SetMap(map_with_box);
    return model.MeanBeamLikelihood(scan, scanner) / fits;
  };
  EXPECT_LT(ratio(*beam), 0.9);     // beams pass where the map has the box
  EXPECT_GT(ratio(*field), 0.999);  // they end on the wall behind it, which is still there
}

TEST(BeamModelTest, NeverUnderflowsOnAHugeScan) {
  const core::OccupancyGrid room = Room();
  core::LaserScan scan = PerfectScan(room, {3.0, 2.0, 0.0}, 20000);
  for (float& r : scan.ranges_m) r = 0.2f;  // every beam contradicts the map
  BeamModelOptions o;
  o.beam_stride = 1;
  const auto model = MakeBeamModel(o);
  model->SetMap(room);
  const ScanScore s = model->Score(scan, {3.0, 2.0, 0.0});
  EXPECT_EQ(s.beams_used, 20000);
  EXPECT_TRUE(std::isfinite(s.log_likelihood));
  EXPECT_LT(s.log_likelihood, -10000.0);  // the product would be exp(-20000) = 0.0
  EXPECT_GT(s.mean_beam_likelihood, 0.0);
  EXPECT_LT(s.mean_beam_likelihood, 0.1);
}

TEST(BeamModelTest, SubsamplesWithTheStride) {
  const core::OccupancyGrid room = Room();
  const core::LaserScan scan = PerfectScan(room, {3.0, 2.0, 0.0}, 361);
  BeamModelOptions o;
  o.beam_stride = 4;
  const auto model = MakeBeamModel(o);
  model->SetMap(room);
  EXPECT_EQ(model->Score(scan, {3.0, 2.0, 0.0}).beams_used, 91);  // 0, 4, ..., 360
}

TEST(BeamModelTest, CountsBadRangesAndNeverReturnsGarbage) {
  const core::OccupancyGrid room = Room();
  const core::Pose2 pose(3.0, 2.0, 0.0);
  core::LaserScan scan = PerfectScan(room, pose);
  scan.ranges_m[0] = NAN;
  scan.ranges_m[1] = -1.0f;
  scan.ranges_m[2] = 0.0f;
  scan.ranges_m[3] = -INFINITY;
  scan.ranges_m[4] = 0.01f;  // below range_min_m
  scan.ranges_m[5] = INFINITY;
  BeamModelOptions o;
  o.beam_stride = 1;
  const auto model = MakeBeamModel(o);
  model->SetMap(room);
  const ScanScore s = model->Score(scan, pose);
  EXPECT_EQ(s.beams_invalid, 5);
  EXPECT_EQ(s.beams_no_return, 1);
  EXPECT_EQ(s.beams_used, 355);
  EXPECT_TRUE(std::isfinite(s.mean_beam_likelihood));
  // Nothing usable, a malformed header, a non-finite pose, no map: NaN ("no information").
  for (float& r : scan.ranges_m) r = NAN;
  EXPECT_TRUE(std::isnan(model->MeanBeamLikelihood(scan, pose)));
  core::LaserScan bad_header = PerfectScan(room, pose);
  bad_header.angle_increment_rad = 0.0;
  EXPECT_TRUE(std::isnan(model->MeanBeamLikelihood(bad_header, pose)));
  const core::LaserScan good = PerfectScan(room, pose);
  EXPECT_TRUE(std::isnan(model->MeanBeamLikelihood(good, core::Pose2(kNaN, 0, 0))));
  EXPECT_GT(model->MeanBeamLikelihood(good, core::Pose2(1e300, -1e300, 0)), 0.0);  // off grid
  model->SetMap(core::OccupancyGrid());
  EXPECT_TRUE(std::isnan(model->MeanBeamLikelihood(good, pose)));
}

TEST(BeamModelTest, ValidateNamesTheBadField) {
  BeamModelOptions o;
  o.sigma_hit_m = -0.1;
  EXPECT_NE(o.Validate().message().find("BeamModelOptions.sigma_hit_m"), std::string::npos);
  o = BeamModelOptions();
  o.beam_stride = 0;
  EXPECT_NE(o.Validate().message().find("beam_stride"), std::string::npos);
  o = BeamModelOptions();
  o.z_hit = o.z_short = o.z_max = o.z_rand = 0.0;
  EXPECT_FALSE(o.Validate().ok());
  o = BeamModelOptions();
  o.lambda_short_per_m = kNaN;
  EXPECT_NE(o.Validate().message().find("lambda_short_per_m"), std::string::npos);
  EXPECT_TRUE(BeamModelOptions().Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
