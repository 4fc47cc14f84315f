#include "aggregator/alignment/placement.h"

#include <gtest/gtest.h>

#include "aggregator/aggregator.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

TEST(PlacementTest, EvidenceLandsWhereTheAnchorPutsIt) {
  core::TempMap map;
  map.vehicle_id = "v1";
  map.grid = core::OccupancyGrid(core::GridGeometry(0.05, 20, 10));
  map.grid.SetLogOdds({3, 2}, 4.0f);
  map.anchor_in_map = core::Pose2(1.0, 2.0, M_PI / 2);  // T turned by 90 degrees
  const core::GridGeometry hall(0.05, 100, 100);
  ASSERT_TRUE(CheckTempMap(map, hall, {}).ok());
  const PlacedEvidence e = PlaceEvidence(map, {}, hall);
  // The 20 x 10 grid, turned (corners on a cell boundary take the next cell in too).
  EXPECT_GE(e.window.width, 10);
  EXPECT_LE(e.window.width, 11);
  EXPECT_GE(e.window.height, 20);
  EXPECT_LE(e.window.height, 21);
  // Temporary cell (3, 2) has its centre at (0.175, 0.125) in T: (0.875, 2.175) in the map.
  const core::CellIndex c = hall.WorldToCell({0.875, 2.175});
  EXPECT_FLOAT_EQ(e.at(c), 4.0f);
  int set = 0;
  for (float l : e.log_odds) set += l != 0.0f;
  EXPECT_EQ(set, 1);
}

class BadInputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    hall_ = testing::HallMap();
    auto aggregator = Aggregator::Create(hall_, {});
    ASSERT_TRUE(aggregator.ok());
    aggregator_.emplace(std::move(aggregator).value());
    testing::TempMapSpec spec;
    spec.start = {4.013, 4.027, 0.0};
    spec.scans = 5;
    good_ = testing::BuildTempMap(hall_, spec);
  }
  // Submits and expects a rejection naming `words`, with the current map untouched.
  void ExpectRejected(const core::TempMap& map, const std::string& words) {
    const auto report = aggregator_->Submit(map, 1.0);
    ASSERT_TRUE(report.ok());
    EXPECT_FALSE(report->accepted);
    EXPECT_EQ(report->reason, RejectReason::kInvalidTempMap);
    EXPECT_NE(report->reason_text.find(words), std::string::npos) << report->reason_text;
    EXPECT_EQ(aggregator_->store().version(), 0u);
    EXPECT_EQ(aggregator_->store().current_map().cells(), hall_.cells());
    EXPECT_TRUE(report->delta.tiles.empty());
  }

  core::OccupancyGrid hall_;
  std::optional<Aggregator> aggregator_;
  core::TempMap good_;
};

TEST_F(BadInputTest, AnotherResolution) {
  core::TempMap map = good_;
  map.grid = core::OccupancyGrid(core::GridGeometry(0.1, 100, 100, good_.grid.geometry().origin()));
  map.grid.SetLogOdds({50, 50}, 3.0f);
  ExpectRejected(map, "resolution");
}

TEST_F(BadInputTest, OutsideTheStaticMap) {
  core::TempMap map = good_;
  map.anchor_in_map.x_m += 40.0;
  ExpectRejected(map, "outside the static map");
}

TEST_F(BadInputTest, AbsurdSize) {
  core::TempMap map = good_;
  map.grid = core::OccupancyGrid(core::GridGeometry(0.05, 2100, 2100));  // 105 m a side
  ExpectRejected(map, "exceeds the limits");
}

TEST_F(BadInputTest, NanAnchorPose) {
  core::TempMap map = good_;
  map.anchor_in_map.theta_rad = std::nan("");
  ExpectRejected(map, "anchor pose is not finite");
}

TEST_F(BadInputTest, NonFiniteCellAndMissingVehicle) {
  core::TempMap map = good_;
  map.grid.mutable_cells()[7] = INFINITY;
  ExpectRejected(map, "non-finite cell");
  map = good_;
  map.vehicle_id.clear();
  ExpectRejected(map, "vehicle id");
  map = good_;
  map.grid = core::OccupancyGrid(good_.grid.geometry());
  ExpectRejected(map, "observed nothing");
}

TEST_F(BadInputTest, TheGoodMapIsAcceptedAfterAllThat) {
  const auto report = aggregator_->Submit(good_, 1.0);
  ASSERT_TRUE(report.ok());
  EXPECT_TRUE(report->accepted) << report->reason_text;
  EXPECT_EQ(aggregator_->store().version(), 1u);
}

// The required behaviour: a featureless temporary map is rejected with its reason.
TEST_F(BadInputTest, FeaturelessMapIsRejectedWithItsReason) {
  // A big open floor with one pallet in the middle: the vehicle sees no wall.
  core::OccupancyGrid floor(core::GridGeometry(0.05, 400, 400));
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) floor.SetState({x, y}, core::CellState::kFree);
  const testing::Box pallet{{10.0, 10.0}, {1.2, 0.8}};
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x)
      if (testing::InBoxes({pallet}, floor.geometry().CellCenter({x, y})))
        floor.SetState({x, y}, core::CellState::kOccupied);
  testing::TempMapSpec spec;
  spec.start = {6.013, 9.027, 0.0};
  spec.grid_m = 8.0;  // the walls lie beyond what the map covers
  core::TempMap map = testing::BuildTempMap(floor, spec);
  map.anchor_in_map = core::Pose2(6.013, 9.027, 0.0);  // placed inside the hall
  const auto report = aggregator_->Submit(map, 1.0);
  ASSERT_TRUE(report.ok());
  EXPECT_FALSE(report->accepted);
  EXPECT_EQ(report->reason, RejectReason::kTooFewStaticLines);
  EXPECT_NE(report->reason_text.find("static lines matched"), std::string::npos);
  EXPECT_EQ(aggregator_->store().version(), 0u);
  EXPECT_EQ(aggregator_->store().current_map().cells(), hall_.cells());
  EXPECT_EQ(aggregator_->stats().rejected, 1);
  EXPECT_EQ(aggregator_->stats().rejected_by_reason[size_t(RejectReason::kTooFewStaticLines)], 1);
  EXPECT_STREQ(RejectReasonName(report->reason), "too_few_static_lines");
}

TEST(PlacementOptionsTest, ValidateNamesTheBadField) {
  PlacementOptions o;
  o.min_inside_fraction = 2;
  EXPECT_NE(o.Validate().message().find("min_inside_fraction"), std::string::npos);
  AggregatorOptions a;
  a.merge.static_clearance_m = -1;
  EXPECT_NE(a.Validate().message().find("static_clearance_m"), std::string::npos);
  EXPECT_FALSE(Aggregator::Create(testing::HallMap(), a).ok());
}

}  // namespace
}  // namespace fleetmap::aggregator
