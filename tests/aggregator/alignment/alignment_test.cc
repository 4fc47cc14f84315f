#include "aggregator/alignment/alignment.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "aggregator/aggregator.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

using testing::BuildTempMap;
using testing::HallMap;
using testing::TempMapSpec;

struct Residual {
  double cells = 0.0;
  double deg = 0.0;
};

Residual AlignAndMeasure(const Aggregator& aggregator, const core::TempMap& map,
                         const core::Pose2& truth, Assessment* out = nullptr) {
  const Assessment a = aggregator.Assess(map);
  if (out) *out = a;
  const core::Pose2 e = core::Between(truth, a.alignment.correction * map.anchor_in_map);
  return {std::hypot(e.x_m, e.y_m) / testing::kRes, std::abs(e.theta_rad) * 180 / M_PI};
}

// Anchor errors up to 0.3 m and 3 degrees, which the alignment must correct, from a few start
// poses.
std::vector<TempMapSpec> Cases() {
  // Off the cell boundaries: core::RayCaster can stall on a ray along a boundary (a known limit).
  const core::Pose2 starts[] = {
      {4.013, 4.027, 0.0}, {15.517, 9.011, M_PI / 2}, {9.021, 16.007, M_PI}};
  const core::Pose2 errors[] = {{0.3, -0.2, 3 * M_PI / 180},
                                {-0.25, 0.15, -2.5 * M_PI / 180},
                                {0.05, 0.28, 1.5 * M_PI / 180},
                                {-0.2, -0.2, -3 * M_PI / 180}};
  std::vector<TempMapSpec> cases;
  for (const core::Pose2& s : starts) {
    for (const core::Pose2& e : errors) {
      TempMapSpec spec;
      spec.start = s;
      spec.anchor_error = e;
      cases.push_back(spec);
    }
  }
  return cases;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

class AlignmentTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    world_ = new core::OccupancyGrid(HallMap());
    for (const TempMapSpec& spec : Cases()) maps_->push_back(BuildTempMap(*world_, spec));
  }
  static void TearDownTestSuite() {
    delete world_;
    maps_->clear();
  }
  static core::OccupancyGrid* world_;
  static std::vector<core::TempMap>* maps_;
};
core::OccupancyGrid* AlignmentTest::world_ = nullptr;
std::vector<core::TempMap>* AlignmentTest::maps_ = new std::vector<core::TempMap>();

TEST_F(AlignmentTest, OursCorrectsKnownShiftsAndTurnsWithinTheGoals) {
  auto aggregator = Aggregator::Create(*world_, {});
  ASSERT_TRUE(aggregator.ok()) << aggregator.status().ToString();
  const auto cases = Cases();
  std::vector<double> cells;
  for (size_t i = 0; i < cases.size(); ++i) {
    Assessment a;
    const Residual r = AlignAndMeasure(*aggregator, (*maps_)[i], cases[i].start, &a);
    EXPECT_TRUE(a.accepted()) << i << ": " << a.reason_text;
    EXPECT_LE(r.cells, 1.0) << "case " << i;  // the goal's 95th percentile, for every case
    EXPECT_LE(r.deg, 0.5) << "case " << i;
    cells.push_back(r.cells);
  }
  EXPECT_LE(Median(cells), 0.5);
}

TEST_F(AlignmentTest, PaperModeImprovesOnTheAnchor) {
  AggregatorOptions options;
  options.alignment.mode = AlignmentMode::kPaper;
  auto aggregator = Aggregator::Create(*world_, options);
  ASSERT_TRUE(aggregator.ok());
  const auto cases = Cases();
  std::vector<double> before, after;
  for (size_t i = 0; i < cases.size(); ++i) {
    const core::Pose2 e = core::Between(cases[i].start, (*maps_)[i].anchor_in_map);
    before.push_back(std::hypot(e.x_m, e.y_m) / testing::kRes);
    after.push_back(AlignAndMeasure(*aggregator, (*maps_)[i], cases[i].start).cells);
  }
  EXPECT_LT(Median(after), 0.5 * Median(before));
}

TEST_F(AlignmentTest, ReportsThePapersNumbersAndLineRows) {
  auto aggregator = Aggregator::Create(*world_, {});
  ASSERT_TRUE(aggregator.ok());
  const Assessment a = aggregator->Assess((*maps_)[0]);
  EXPECT_GE(a.alignment.matches.size(), 2u);
  // The correction undoes the anchor error: about -3 degrees.
  EXPECT_NEAR(a.alignment.dtheta_rad * 180 / M_PI, -3.0, 0.5);
  for (const LineMatch& m : a.alignment.matches) {
    EXPECT_LT(std::abs(m.offset_m) / testing::kRes, 3.0);  // the Tables' distance column
    EXPECT_LT(std::abs(m.angle_diff_rad) * 180 / M_PI, 5.0);
  }
}

TEST(AlignmentRotatedHallTest, DominantDirectionsFollowATurnedHall) {
  const double yaw = 25.0 * M_PI / 180;
  const core::OccupancyGrid world = HallMap(yaw);
  auto aggregator = Aggregator::Create(world, {});
  ASSERT_TRUE(aggregator.ok());
  const DominantDirections& d = aggregator->static_features().directions();
  const double primary_deg = d.primary_rad * 180 / M_PI,
               secondary_deg = d.secondary_rad * 180 / M_PI;
  EXPECT_NEAR(std::min(std::abs(primary_deg - 25), std::abs(primary_deg - 115)), 0.0, 1.0);
  EXPECT_NEAR(std::abs(primary_deg - secondary_deg), 90.0, 2.0);
  // A map started inside the turned hall, heading along it.
  TempMapSpec spec;
  const core::Pose2 hall_to_map = core::Pose2(10, 10, yaw) * core::Pose2(-10, -10, 0);
  spec.start = hall_to_map * core::Pose2(5.013, 4.027, 0.0);
  spec.anchor_error = {0.2, -0.25, 2.0 * M_PI / 180};
  const core::TempMap map = BuildTempMap(world, spec);
  Assessment a;
  const Residual r = AlignAndMeasure(*aggregator, map, spec.start, &a);
  EXPECT_TRUE(a.accepted()) << a.reason_text;
  EXPECT_LE(r.cells, 1.0);
  EXPECT_LE(r.deg, 0.5);
}

TEST(AlignmentModeTest, NamesParseBack) {
  EXPECT_EQ(*ParseAlignmentMode("paper"), AlignmentMode::kPaper);
  EXPECT_EQ(*ParseAlignmentMode("ours"), AlignmentMode::kDominantDirections);
  EXPECT_STREQ(AlignmentModeName(AlignmentMode::kPaper), "paper");
  EXPECT_EQ(ParseAlignmentMode("best").status().code(), core::StatusCode::kInvalidArgument);
}

TEST(AlignmentOptionsTest, ValidateNamesTheBadField) {
  AlignmentOptions o;
  o.iterations = 0;
  EXPECT_NE(o.Validate().message().find("iterations"), std::string::npos);
  o = {};
  o.matching.max_normal_offset_m = -1;
  EXPECT_NE(o.Validate().message().find("max_normal_offset_m"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::aggregator
