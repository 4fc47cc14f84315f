#include "core/codec/tile_delta.h"

#include <gtest/gtest.h>

namespace fleetmap::core {
namespace {

OccupancyGrid Hall() {
  OccupancyGrid grid(GridGeometry(0.05, 200, 130));
  for (int y = 0; y < 130; ++y)
    for (int x = 0; x < 200; ++x)
      grid.SetState({x, y}, (x == 0 || y == 0 || x == 199 || y == 129) ? CellState::kOccupied
                                                                       : CellState::kFree);
  return grid;
}

TEST(TileDeltaTest, LayoutClipsEdgeTiles) {
  const TileLayout layout(GridGeometry(0.05, 200, 130), 64);
  EXPECT_EQ(layout.tiles_x(), 4);
  EXPECT_EQ(layout.tiles_y(), 3);
  EXPECT_EQ(layout.Window({3, 2}), (CellWindow{192, 128, 8, 2}));
  EXPECT_EQ(layout.FromLinear(layout.Linear({2, 1})), (TileIndex{2, 1}));
}

TEST(TileDeltaTest, UnchangedGridHasEmptyDelta) {
  const OccupancyGrid a = Hall();
  EXPECT_TRUE(EncodeChangedTiles(a, a).empty());
}

TEST(TileDeltaTest, DeltaHoldsOnlyTouchedTilesAndReproducesTheNewGrid) {
  const OccupancyGrid before = Hall();
  OccupancyGrid after = before;
  for (int y = 60; y < 70; ++y)
    for (int x = 60; x < 70; ++x)
      after.SetState({x, y}, CellState::kOccupied);  // tiles (0..1, 0..1)
  const auto delta = EncodeChangedTiles(before, after);
  ASSERT_EQ(delta.size(), 4u);
  OccupancyGrid receiver = before;
  ASSERT_TRUE(ApplyTiles(delta, 64, receiver).ok());
  for (int y = 0; y < 130; ++y)
    for (int x = 0; x < 200; ++x) ASSERT_EQ(receiver.state({x, y}), after.state({x, y}));
}

TEST(TileDeltaTest, KeyframeRebuildsTheWholeGrid) {
  const OccupancyGrid grid = Hall();
  const auto tiles = EncodeAllTiles(grid);
  EXPECT_EQ(tiles.size(), 12u);
  OccupancyGrid receiver(grid.geometry());
  ASSERT_TRUE(ApplyTiles(tiles, 64, receiver).ok());
  EXPECT_EQ(receiver.CountState(CellState::kOccupied), grid.CountState(CellState::kOccupied));
  EXPECT_EQ(receiver.CountState(CellState::kUnknown), 0);
}

TEST(TileDeltaTest, OneCorruptTileMeansNoTileIsApplied) {
  const OccupancyGrid grid = Hall();
  auto tiles = EncodeAllTiles(grid);
  tiles.back().frame[40] ^= 0xFF;
  OccupancyGrid receiver(grid.geometry());
  const Status s = ApplyTiles(tiles, 64, receiver);
  EXPECT_EQ(s.code(), StatusCode::kDataLoss);
  EXPECT_NE(s.message().find("tile (3, 2)"), std::string::npos) << s.message();
  EXPECT_EQ(receiver.CountState(CellState::kUnknown), 200 * 130);
}

TEST(TileDeltaTest, TileWhoseFrameDoesNotFitItsIndexIsRejected) {
  const OccupancyGrid grid = Hall();
  auto tiles = EncodeAllTiles(grid);
  tiles[0].index = {1, 0};  // frame of tile (0,0) claimed as (1,0)
  OccupancyGrid receiver(grid.geometry());
  EXPECT_FALSE(ApplyTiles({tiles[0]}, 64, receiver).ok());
  tiles[0].index = {9, 9};
  EXPECT_EQ(ApplyTiles({tiles[0]}, 64, receiver).code(), StatusCode::kOutOfRange);
}

TEST(TileDeltaTest, OptionsValidate) {
  TileOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.tile_size_cells = 0;
  EXPECT_FALSE(o.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::core
