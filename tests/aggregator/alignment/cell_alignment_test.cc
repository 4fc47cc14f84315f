#include "aggregator/alignment/cell_alignment.h"

#include <gtest/gtest.h>

#include "aggregator/aggregator.h"
#include "aggregator/alignment/alignment_steps.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

using testing::BuildTempMap;
using testing::kRes;
using testing::TempMapSpec;

// A round room 19 m across with round pillars: no straight wall anywhere (a mixed hall's
// curved walls, an office's clutter). Unknown outside the wall.
core::OccupancyGrid RoundRoom() {
  core::OccupancyGrid grid(core::GridGeometry(kRes, testing::kHallCells, testing::kHallCells));
  const Eigen::Vector2d centre(10, 10);
  const std::vector<std::pair<Eigen::Vector2d, double>> pillars = {{{7.0, 11.5}, 0.35},
                                                                   {{12.5, 7.5}, 0.3},
                                                                   {{11.0, 13.0}, 0.4},
                                                                   {{5.5, 6.0}, 0.25},
                                                                   {{14.0, 12.0}, 0.3}};
  for (int y = 0; y < testing::kHallCells; ++y)
    for (int x = 0; x < testing::kHallCells; ++x) {
      const Eigen::Vector2d p = grid.geometry().CellCenter({x, y});
      const double r = (p - centre).norm();
      bool solid = r >= 9.5 && r < 9.7;
      for (const auto& [at, radius] : pillars) solid = solid || (p - at).norm() < radius;
      grid.SetState({x, y}, solid     ? core::CellState::kOccupied
                            : r < 9.5 ? core::CellState::kFree
                                      : core::CellState::kUnknown);
    }
  return grid;
}

struct Placement {
  double cells = 0.0, deg = 0.0;
};
Placement Off(const core::Pose2& placed, const core::Pose2& truth) {
  const core::Pose2 e = core::Between(truth, placed);
  return {std::hypot(e.x_m, e.y_m) / kRes, std::abs(e.theta_rad) * 180 / M_PI};
}

// Surface cells of a temporary map, in its frame (what the aggregator aligns).
std::vector<Eigen::Vector2d> Surface(const core::TempMap& map) {
  std::vector<Eigen::Vector2d> points;
  const core::GridGeometry& g = map.grid.geometry();
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x)
      if (map.grid.log_odds({x, y}) >= 3.0f) points.push_back(g.CellCenter({x, y}));
  return points;
}

class CellAlignmentTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { room_ = new core::OccupancyGrid(RoundRoom()); }
  static void TearDownTestSuite() { delete room_; }
  static core::TempMap Map(const core::Pose2& anchor_error) {
    TempMapSpec spec;
    spec.start = {6.013, 9.027, 0.3};
    spec.anchor_error = anchor_error;
    return BuildTempMap(*room_, spec);
  }
  static core::OccupancyGrid* room_;
};
core::OccupancyGrid* CellAlignmentTest::room_ = nullptr;

TEST_F(CellAlignmentTest, FindsAKnownShiftAndTurnWhereThereAreNoLines) {
  auto features = StaticMapFeatures::Compute(*room_);
  ASSERT_TRUE(features.ok());
  for (const core::Pose2& error :
       {core::Pose2(0.12, -0.09, 1.5 * M_PI / 180), core::Pose2(-0.2, 0.1, -2.0 * M_PI / 180)}) {
    const core::TempMap map = Map(error);
    const CellAlignment c = AlignCells(*features, Surface(map), map.anchor_in_map, {});
    const Placement before = Off(map.anchor_in_map, {6.013, 9.027, 0.3});
    const Placement after = Off(c.correction * map.anchor_in_map, {6.013, 9.027, 0.3});
    EXPECT_GT(before.cells, 2.0);
    EXPECT_LT(after.cells, 1.0) << "anchor off " << before.cells << " cells";
    EXPECT_LT(after.deg, 0.3);
    EXPECT_GT(c.score, c.at_anchor);
    EXPECT_GE(c.distinctness, 0.3);
    EXPECT_FALSE(c.at_edge);
  }
}

// A good anchor is not made worse.
TEST_F(CellAlignmentTest, AGoodAnchorStandsWithinAFractionOfACell) {
  auto features = StaticMapFeatures::Compute(*room_);
  ASSERT_TRUE(features.ok());
  const core::TempMap map = Map({});
  const CellAlignment c = AlignCells(*features, Surface(map), map.anchor_in_map, {});
  const Placement after = Off(c.correction * map.anchor_in_map, {6.013, 9.027, 0.3});
  EXPECT_LT(after.cells, 0.5);
  EXPECT_LT(after.deg, 0.2);
}

// Nothing of the static map near the points: a flat score, not trusted.
TEST_F(CellAlignmentTest, NothingToMatchIsNotDistinct) {
  auto features = StaticMapFeatures::Compute(*room_);
  ASSERT_TRUE(features.ok());
  const std::vector<Eigen::Vector2d> far = {{0.5, 0.0}, {0.6, 0.0}, {0.7, 0.1}};
  const CellAlignment c = AlignCells(*features, far, core::Pose2(10, 10, 0), {});
  EXPECT_EQ(c.distinctness, 0.0);
  EXPECT_NEAR(c.correction.x_m, 0.0, 1e-12);  // a flat score keeps the anchor
}

// The aggregator: lines reject a line-free map; the cells align it, and the report says so.
TEST_F(CellAlignmentTest, TheAggregatorAlignsALineFreeMapByItsCells) {
  const core::TempMap map = Map({0.12, -0.09, 1.5 * M_PI / 180});
  AggregatorOptions lines_only;
  lines_only.cell_alignment.use = CellAlignmentUse::kOff;
  auto without = Aggregator::Create(*room_, lines_only);
  ASSERT_TRUE(without.ok());
  EXPECT_FALSE(without->Assess(map).accepted());
  auto with = Aggregator::Create(*room_, {});
  ASSERT_TRUE(with.ok());
  const Assessment a = with->Assess(map);
  ASSERT_TRUE(a.accepted()) << a.reason_text;
  EXPECT_NE(a.reason_text.find("aligned by cells"), std::string::npos) << a.reason_text;
  EXPECT_LT(Off(a.alignment.correction * map.anchor_in_map, {6.013, 9.027, 0.3}).cells, 1.0);
  const auto report = with->Submit(map, 1.0);
  ASSERT_TRUE(report.ok());
  EXPECT_TRUE(report->accepted);
  EXPECT_EQ(with->store().version(), 1u);
}

// Another method's pose is judged by where it scores in the search's window.
TEST(CellAlignmentRivalTest, APoseAlongACorridorFitsAsTheBestAndOneAcrossItDoesNot) {
  const core::OccupancyGrid grid = testing::CorridorMap(kRes / 2);
  auto features = StaticMapFeatures::Compute(grid);
  ASSERT_TRUE(features.ok());
  std::vector<Eigen::Vector2d> walls;  // in the map's frame T, the anchor at (10, 9)
  for (double x = -2.0; x <= 2.0; x += kRes) walls.insert(walls.end(), {{x, -1.0}, {x, 1.0}});
  const core::Pose2 anchor(10.0, 9.0, 0.0);
  const CellAlignmentOptions o;
  const CellAlignment c = AlignCells(*features, walls, anchor, o);
  EXPECT_LT(c.distinctness, 0.3);  // ambiguous along the corridor
  const auto relative = [&](const core::Pose2& correction) {
    return c.Relative(CellScoreAt(*features, walls, anchor, correction, o));
  };
  EXPECT_NEAR(relative({}), 1.0, 0.02);
  EXPECT_GE(relative({0.2, 0.0, 0.0}), o.lines_min_relative_score);
  EXPECT_LT(relative({0.0, 0.15, 0.0}), o.lines_min_relative_score);
  EXPECT_LT(relative({0.0, 0.0, 2.0 * M_PI / 180}), o.lines_min_relative_score);
}

TEST(CellAlignmentOptionsTest, BadOptionsAreNamed) {
  CellAlignmentOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.step_m = 0;
  EXPECT_NE(o.Validate().message().find("step_m"), std::string::npos);
  o = CellAlignmentOptions();
  o.range_m = -1;
  EXPECT_NE(o.Validate().message().find("range_m"), std::string::npos);
  o = CellAlignmentOptions();
  o.lines_min_relative_score = 1.5;
  EXPECT_NE(o.Validate().message().find("lines_min_relative_score"), std::string::npos);
  AggregatorOptions a;
  a.cell_alignment.max_points = 1;
  EXPECT_FALSE(a.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::aggregator
