#include "core/map/occupancy_grid.h"

#include <gtest/gtest.h>

namespace fleetmap::core {
namespace {

TEST(OccupancyGridTest, StartsUnknown) {
  const OccupancyGrid grid(GridGeometry(0.05, 20, 20));
  EXPECT_EQ(grid.CountState(CellState::kUnknown), 400);
  EXPECT_DOUBLE_EQ(grid.probability({3, 3}), 0.5);
}

TEST(OccupancyGridTest, LogOddsUpdatesAddAndClamp) {
  OccupancyGrid grid(GridGeometry(0.05, 20, 20), LogOddsLimits{-2.0f, 3.0f});
  grid.AddLogOdds({1, 2}, 0.85f);
  grid.AddLogOdds({1, 2}, 0.85f);
  EXPECT_FLOAT_EQ(grid.log_odds({1, 2}), 1.7f);
  for (int i = 0; i < 10; ++i) grid.AddLogOdds({1, 2}, 0.85f);
  EXPECT_FLOAT_EQ(grid.log_odds({1, 2}), 3.0f);
  // Clamping lets a few free observations clear a long-standing obstacle.
  for (int i = 0; i < 20; ++i) grid.AddLogOdds({1, 2}, -0.4f);
  EXPECT_FLOAT_EQ(grid.log_odds({1, 2}), -2.0f);
  EXPECT_EQ(grid.state({1, 2}), CellState::kFree);
}

TEST(OccupancyGridTest, TriStateFollowsMapServerThresholds) {
  OccupancyGrid grid(GridGeometry(0.05, 4, 1));
  grid.SetLogOdds({0, 0}, ProbabilityToLogOdds(0.66));
  grid.SetLogOdds({1, 0}, ProbabilityToLogOdds(0.64));
  grid.SetLogOdds({2, 0}, ProbabilityToLogOdds(0.20));
  grid.SetLogOdds({3, 0}, ProbabilityToLogOdds(0.19));
  EXPECT_EQ(grid.state({0, 0}), CellState::kOccupied);
  EXPECT_EQ(grid.state({1, 0}), CellState::kUnknown);
  EXPECT_EQ(grid.state({2, 0}), CellState::kUnknown);
  EXPECT_EQ(grid.state({3, 0}), CellState::kFree);
  OccupancyThresholds loose;
  loose.occupied_probability = 0.6;
  EXPECT_EQ(grid.state({1, 0}, loose), CellState::kOccupied);
}

TEST(OccupancyGridTest, SetStateWritesCanonicalValues) {
  OccupancyGrid grid(GridGeometry(0.05, 3, 1));
  grid.SetState({0, 0}, CellState::kOccupied);
  grid.SetState({1, 0}, CellState::kFree);
  grid.SetState({2, 0}, CellState::kUnknown);
  EXPECT_EQ(grid.log_odds({0, 0}), grid.limits().max_log_odds);
  EXPECT_EQ(grid.log_odds({1, 0}), grid.limits().min_log_odds);
  EXPECT_EQ(grid.log_odds({2, 0}), 0.0f);
  EXPECT_EQ(grid.CountState(CellState::kOccupied), 1);
}

TEST(OccupancyGridTest, ThresholdValidation) {
  EXPECT_TRUE(OccupancyThresholds{}.Validate().ok());
  EXPECT_FALSE((OccupancyThresholds{0.2, 0.6}).Validate().ok());
  EXPECT_FALSE((OccupancyThresholds{1.0, 0.1}).Validate().ok());
  EXPECT_FALSE((LogOddsLimits{1.0f, 2.0f}).Validate().ok());
}

}  // namespace
}  // namespace fleetmap::core
