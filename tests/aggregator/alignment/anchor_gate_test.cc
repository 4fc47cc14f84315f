#include "aggregator/alignment/anchor_gate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "aggregator/aggregator.h"
#include "core/pose_covariance.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

constexpr double kDeg = M_PI / 180;

// The covariance test at the 99 % limit of an honest covariance (off by default).
AnchorGateOptions Gated() {
  AnchorGateOptions o;
  o.max_mahalanobis_sq = 11.34;
  return o;
}

AnchorGateOptions NoFloor() {
  AnchorGateOptions o = Gated();
  o.floor_sigma_xy_m = 0.0;
  o.floor_sigma_theta_rad = 0.0;
  return o;
}

TEST(AnchorGateTest, AMoveWithinTheCovarianceIsTakenAndOneBeyondItIsNot) {
  const core::Pose2 anchor(5.0, 3.0, 0.4);
  const Eigen::Matrix3d c = core::DiagonalCovariance(0.1, 2 * kDeg);
  // 0.2 m along x: two sigmas, squared Mahalanobis 4.
  const AnchorGateVerdict near = JudgeCorrection(anchor, c, {0.2, 0.0, 0.0}, 0.7, 0.8, NoFloor());
  EXPECT_TRUE(near.take_correction);
  EXPECT_NEAR(near.mahalanobis_sq, 4.0, 1e-9);
  EXPECT_TRUE(near.explanation.empty());
  // 0.4 m: four sigmas, 16 > 11.34.
  const AnchorGateVerdict far = JudgeCorrection(anchor, c, {0.4, 0.0, 0.0}, 0.7, 0.8, NoFloor());
  EXPECT_FALSE(far.take_correction);
  EXPECT_NEAR(far.mahalanobis_sq, 16.0, 1e-9);
  EXPECT_NE(far.explanation.find("anchor stands"), std::string::npos) << far.explanation;
}

TEST(AnchorGateTest, ATurnMovesTheAnchorAboutTheStaticOrigin) {
  // A correction turning about the static frame's origin moves an anchor far from it.
  const core::Pose2 anchor(10.0, 0.0, 0.0);
  const Eigen::Matrix3d c = core::DiagonalCovariance(0.1, 5 * kDeg);
  const AnchorGateVerdict v =
      JudgeCorrection(anchor, c, {0.0, 0.0, 1.0 * kDeg}, 0.7, 0.8, NoFloor());
  // The anchor moves 0.175 m across and turns 1 degree.
  EXPECT_NEAR(v.mahalanobis_sq, std::pow(10 * std::sin(kDeg) / 0.1, 2) + 0.04, 0.01);
}

TEST(AnchorGateTest, TheFloorWidensAnOverconfidentCovariance) {
  const core::Pose2 anchor(1.0, 1.0, 0.0);
  const Eigen::Matrix3d tight = core::DiagonalCovariance(0.001, 0.001);  // claims a millimetre
  AnchorGateOptions o = Gated();
  o.floor_sigma_xy_m = 0.05;
  EXPECT_TRUE(JudgeCorrection(anchor, tight, {0.05, 0.05, 0.0}, 0.7, 0.8, o).take_correction);
  EXPECT_FALSE(
      JudgeCorrection(anchor, tight, {0.05, 0.05, 0.0}, 0.7, 0.8, NoFloor()).take_correction);
}

TEST(AnchorGateTest, ASingularCovarianceWithoutFloorKeepsTheAnchorForAnyMove) {
  const AnchorGateVerdict v = JudgeCorrection({1.0, 1.0, 0.0}, Eigen::Matrix3d::Zero(),
                                              {0.01, 0.0, 0.0}, 0.7, 0.8, NoFloor());
  EXPECT_FALSE(v.take_correction);
  EXPECT_TRUE(std::isinf(v.mahalanobis_sq));
  EXPECT_TRUE(JudgeCorrection({1.0, 1.0, 0.0}, Eigen::Matrix3d::Zero(), {}, 0.7, 0.8, NoFloor())
                  .take_correction);
}

TEST(AnchorGateTest, ByDefaultACorrectionThatFitsWorseIsNotTakenWhateverTheCovariance) {
  const AnchorGateOptions o;
  EXPECT_TRUE(std::isinf(o.max_mahalanobis_sq));
  const Eigen::Matrix3d tight = core::DiagonalCovariance(0.001, 0.001);
  const AnchorGateVerdict far = JudgeCorrection({}, tight, {0.3, 0, 0}, 0.70, 0.70, o);
  EXPECT_TRUE(far.take_correction);     // measured, not tested
  EXPECT_GT(far.mahalanobis_sq, 30.0);  // 0.3 m against the 0.05 m floor
  const AnchorGateVerdict worse = JudgeCorrection({}, tight, {0.3, 0, 0}, 0.70, 0.69, o);
  EXPECT_FALSE(worse.take_correction);
  EXPECT_NE(worse.explanation.find("-0.010 more"), std::string::npos) << worse.explanation;
}

TEST(AnchorGateTest, ACorrectionMustFitBetterByTheMargin) {
  AnchorGateOptions o;
  o.min_explained_gain = 0.02;
  const Eigen::Matrix3d c = core::DiagonalCovariance(0.1, 2 * kDeg);
  EXPECT_TRUE(JudgeCorrection({}, c, {0.05, 0, 0}, 0.70, 0.73, o).take_correction);
  const AnchorGateVerdict v = JudgeCorrection({}, c, {0.05, 0, 0}, 0.70, 0.71, o);
  EXPECT_FALSE(v.take_correction);
  EXPECT_NE(v.explanation.find("0.010 more"), std::string::npos) << v.explanation;
}

TEST(AnchorGateTest, WithoutACovarianceOrWhenOffEveryCorrectionIsTaken) {
  EXPECT_TRUE(JudgeCorrection({}, std::nullopt, {5.0, 0, 0}, 0.7, 0.2, {}).take_correction);
  AnchorGateOptions off = Gated();
  off.enabled = false;
  const AnchorGateVerdict v =
      JudgeCorrection({}, core::DiagonalCovariance(0.1, 0.01), {0.5, 0, 0}, 0.7, 0.2, off);
  EXPECT_TRUE(v.take_correction);
  EXPECT_NEAR(v.mahalanobis_sq, 25.0 * 0.01 / (0.01 + 0.0025), 1e-9);  // still measured
}

TEST(AnchorGateTest, AnUnalignedAnchorStandsOnlyWhereTheVehicleKnewItWell) {
  AnchorGateOptions o;
  o.stand_max_sigma_xy_m = 0.03;
  o.stand_max_sigma_theta_rad = 1.0 * kDeg;
  const AnchorGateVerdict known =
      JudgeUnalignedAnchor(core::DiagonalCovariance(0.02, 0.5 * kDeg), o);
  EXPECT_NE(known.explanation.find("anchor stands"), std::string::npos);
  EXPECT_NE(known.explanation.find("0.020 m"), std::string::npos) << known.explanation;
  EXPECT_TRUE(
      JudgeUnalignedAnchor(core::DiagonalCovariance(0.05, 0.5 * kDeg), o).explanation.empty());
  EXPECT_TRUE(
      JudgeUnalignedAnchor(core::DiagonalCovariance(0.02, 2.0 * kDeg), o).explanation.empty());
  EXPECT_TRUE(JudgeUnalignedAnchor(std::nullopt, o).explanation.empty());
  // Correlated: each axis within 0.03 m, the long axis of the ellipse 0.039 m.
  Eigen::Matrix3d correlated = core::DiagonalCovariance(0.028, 0.5 * kDeg);
  correlated(0, 1) = correlated(1, 0) = 0.0007;
  EXPECT_TRUE(JudgeUnalignedAnchor(correlated, o).explanation.empty());
  o.stand_max_sigma_xy_m = 0.0;  // off
  EXPECT_TRUE(JudgeUnalignedAnchor(core::DiagonalCovariance(0.001, 0.001), o).explanation.empty());
}

TEST(AnchorGateTest, OptionsOutOfRangeAreRefused) {
  EXPECT_TRUE(AnchorGateOptions{}.Validate().ok());
  AnchorGateOptions o;
  o.floor_sigma_xy_m = -0.01;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.floor_sigma_theta_rad = NAN;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.max_mahalanobis_sq = 0.0;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.min_explained_gain = -1.0;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.stand_max_sigma_xy_m = -0.1;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.stand_max_sigma_theta_rad = INFINITY;
  EXPECT_FALSE(o.Validate().ok());
}

// The aggregator on the test hall: a map whose anchor is 0.15 m and 1.5 degrees off.
class AnchorGateHallTest : public ::testing::Test {
 protected:
  void SetUp() override {
    hall_ = testing::HallMap();
    spec_.start = {4.013, 4.027, 0.0};
    spec_.anchor_error = {0.12, -0.09, 1.5 * kDeg};
  }
  // The placed map's error at its start: metres, degrees.
  std::pair<double, double> Error(const core::TempMap& map, const Assessment& a) const {
    const core::Pose2 placed = a.alignment.correction * map.anchor_in_map;
    return {std::hypot(placed.x_m - spec_.start.x_m, placed.y_m - spec_.start.y_m),
            std::abs(core::NormalizeAngle(placed.theta_rad - spec_.start.theta_rad)) / kDeg};
  }
  core::OccupancyGrid hall_;
  testing::TempMapSpec spec_;
};

TEST_F(AnchorGateHallTest, ACovarianceThatAllowsTheErrorLetsTheCorrectionFixIt) {
  core::TempMap map = testing::BuildTempMap(hall_, spec_);
  map.anchor_covariance = core::DiagonalCovariance(0.1, 1.5 * kDeg);
  auto aggregator = Aggregator::Create(hall_, {});
  ASSERT_TRUE(aggregator.ok());
  const Assessment a = aggregator->Assess(map);
  ASSERT_TRUE(a.accepted()) << a.reason_text;
  EXPECT_FALSE(a.confidence.anchor_stands);
  EXPECT_LT(a.confidence.anchor_mahalanobis_sq, 11.34);
  const auto [m, deg] = Error(map, a);
  EXPECT_LT(m, 0.05);
  EXPECT_LT(deg, 0.3);
}

TEST_F(AnchorGateHallTest, ACovarianceThatDeniesTheMoveKeepsTheAnchor) {
  core::TempMap map = testing::BuildTempMap(hall_, spec_);
  map.anchor_covariance = core::DiagonalCovariance(0.01, 0.1 * kDeg);
  AggregatorOptions options;
  options.anchor_gate.max_mahalanobis_sq = 11.34;
  options.anchor_gate.floor_sigma_xy_m = 0.01;
  auto aggregator = Aggregator::Create(hall_, options);
  ASSERT_TRUE(aggregator.ok());
  const Assessment a = aggregator->Assess(map);
  ASSERT_TRUE(a.accepted()) << a.reason_text;
  EXPECT_TRUE(a.confidence.anchor_stands);
  EXPECT_GT(a.confidence.anchor_mahalanobis_sq, 11.34);
  EXPECT_NE(a.reason_text.find("anchor stands"), std::string::npos) << a.reason_text;
  EXPECT_NEAR(a.alignment.correction.x_m, 0.0, 1e-12);
  EXPECT_NEAR(a.alignment.correction.theta_rad, 0.0, 1e-12);
  EXPECT_EQ(a.confidence.explained_after, a.confidence.explained_before);
}

// A good anchor with an honest covariance is left alone or improved, never made worse.
TEST_F(AnchorGateHallTest, AGoodAnchorIsNeverMadeWorse) {
  for (const core::Pose2& error : {core::Pose2(0.0, 0.0, 0.0), core::Pose2(0.02, -0.01, 0.002),
                                   core::Pose2(-0.03, 0.02, -0.004)}) {
    spec_.anchor_error = error;
    core::TempMap map = testing::BuildTempMap(hall_, spec_);
    map.anchor_covariance = core::DiagonalCovariance(0.03, 0.3 * kDeg);
    auto aggregator = Aggregator::Create(hall_, {});
    ASSERT_TRUE(aggregator.ok());
    const Assessment a = aggregator->Assess(map);
    ASSERT_TRUE(a.accepted()) << a.reason_text;
    const double before = std::hypot(error.x_m, error.y_m);
    EXPECT_LE(Error(map, a).first, std::max(before, 0.5 * testing::kRes)) << a.reason_text;
  }
}

TEST(AnchorGateCorridorTest, AMapNoCorrectionCanPlaceStandsAtAWellKnownAnchor) {
  const core::OccupancyGrid corridor = testing::CorridorMap(0.1);  // walls that stop rays
  testing::TempMapSpec spec;
  spec.start = {6.013, 9.027, 0.0};
  spec.scans = 20;
  spec.grid_m = 8.0;
  core::TempMap map = testing::BuildTempMap(corridor, spec);
  map.anchor_covariance = core::DiagonalCovariance(0.02, 0.5 * kDeg);
  AggregatorOptions never;
  never.anchor_gate.stand_max_sigma_xy_m = 0.0;
  auto rejecting = Aggregator::Create(corridor, never);
  ASSERT_TRUE(rejecting.ok());
  const Assessment rejected = rejecting->Assess(map);
  ASSERT_FALSE(rejected.accepted());
  EXPECT_FALSE(rejected.confidence.anchor_stands);
  auto standing = Aggregator::Create(corridor, {});  // within 0.03 m and 1 deg by default
  ASSERT_TRUE(standing.ok());
  const Assessment a = standing->Assess(map);
  ASSERT_TRUE(a.accepted()) << a.reason_text;
  EXPECT_TRUE(a.confidence.anchor_stands);
  EXPECT_NE(a.reason_text.find("no correction found"), std::string::npos) << a.reason_text;
  EXPECT_NEAR(a.alignment.correction.x_m, 0.0, 1e-12);
  // A vehicle that knew its anchor only to 0.1 m is still refused.
  map.anchor_covariance = core::DiagonalCovariance(0.1, 0.5 * kDeg);
  EXPECT_FALSE(standing->Assess(map).accepted());
}

}  // namespace
}  // namespace fleetmap::aggregator
