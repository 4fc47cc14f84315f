#include "core/codec/temp_map_tiles.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

namespace fleetmap::core {
namespace {

using ::testing::HasSubstr;

TempMap Sample() {
  TempMap m;
  m.vehicle_id = "cts1";
  m.sequence = 7;
  m.anchor_in_map = Pose2(12.0, 4.0, 0.3);
  m.grid = OccupancyGrid(GridGeometry(0.05, 150, 90, Pose2(-2.0, -1.5, 0)));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> l(-4.0f, 4.0f);
  for (float& c : m.grid.mutable_cells()) c = l(rng);
  m.start_s = 100.0;
  m.end_s = 112.5;
  return m;
}

TEST(TempMapTilesTest, SplitAndAssembleInAnyOrder) {
  const TempMap original = Sample();
  std::vector<TempMapTile> tiles = SplitTempMap(original);
  ASSERT_EQ(tiles.size(), 3u * 2u);  // 150 x 90 cells in 64-cell tiles
  for (const TempMapTile& t : tiles) EXPECT_LT(t.frame.size(), 8000u);  // a few KB each
  std::reverse(tiles.begin(), tiles.end());
  TempMapAssembler assembler;
  std::optional<TempMap> done;
  for (size_t i = 0; i < tiles.size(); ++i) {
    auto r = assembler.Add(tiles[i]);
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    if (i + 1 < tiles.size()) {
      EXPECT_FALSE(r->has_value());
    }
    if (i == 2) {
      EXPECT_EQ(assembler.Received("cts1", 7).size(), 3u);
    }
    if (r->has_value()) done = **r;
  }
  ASSERT_TRUE(done.has_value());
  EXPECT_EQ(assembler.pending(), 0u);
  // Same placement, same cells within the int8 quantum.
  // The aggregator turns a map about its anchor: the anchor itself must survive the trip.
  EXPECT_EQ(done->anchor_in_map.x_m, original.anchor_in_map.x_m);
  EXPECT_EQ(done->anchor_in_map.theta_rad, original.anchor_in_map.theta_rad);
  const GridGeometry a = original.PlacedGeometry(), b = done->PlacedGeometry();
  EXPECT_NEAR(a.origin().x_m, b.origin().x_m, 1e-12);
  EXPECT_NEAR(a.origin().theta_rad, b.origin().theta_rad, 1e-12);
  for (size_t i = 0; i < original.grid.cells().size(); ++i)
    ASSERT_NEAR(done->grid.cells()[i], original.grid.cells()[i], kLogOddsQuantum / 2 + 1e-6);
  EXPECT_EQ(done->end_s, 112.5);
}

TEST(TempMapTilesTest, RepeatedTilesAreHarmless) {
  const auto tiles = SplitTempMap(Sample());
  TempMapAssembler assembler;
  ASSERT_TRUE(assembler.Add(tiles[0]).ok());
  ASSERT_TRUE(assembler.Add(tiles[0]).ok());
  EXPECT_EQ(assembler.Received("cts1", 7), std::vector<int32_t>{0});
}

TEST(TempMapTilesTest, BadTilesAreRefusedWithAReason) {
  const auto tiles = SplitTempMap(Sample());
  TempMapAssembler assembler;
  TempMapTile t = tiles[1];
  t.frame[40] ^= 0xFF;
  EXPECT_THAT(assembler.Add(t).status().message(), HasSubstr("CRC"));
  t = tiles[1];
  t.index = 9;
  EXPECT_FALSE(assembler.Add(t).ok());
  t = tiles[1];
  t.width_cells = 100000;
  t.height_cells = 100000;
  EXPECT_EQ(assembler.Add(t).status().code(), StatusCode::kOutOfRange);
  t = tiles[1];
  t.resolution_m = NAN;
  EXPECT_FALSE(assembler.Add(t).ok());
  t = tiles[1];
  t.tile = tiles[2].tile;  // a frame of one window claimed for another
  EXPECT_FALSE(assembler.Add(t).ok());
  // A tile that disagrees with its map's first tile is refused; the first one is kept.
  ASSERT_TRUE(assembler.Add(tiles[0]).ok());
  t = tiles[1];
  t.anchor_in_map.x_m += 1.0;
  EXPECT_THAT(assembler.Add(t).status().message(), HasSubstr("disagrees"));
  EXPECT_EQ(assembler.Received("cts1", 7).size(), 1u);
}

TEST(TempMapTilesTest, PendingMapsAreBounded) {
  AssemblerOptions options;
  options.max_pending_maps = 2;
  TempMapAssembler assembler(options);
  TempMap m = Sample();
  for (int seq = 1; seq <= 2; ++seq) {
    m.sequence = seq;
    ASSERT_TRUE(assembler.Add(SplitTempMap(m)[0]).ok());
  }
  m.sequence = 3;
  EXPECT_EQ(assembler.Add(SplitTempMap(m)[0]).status().code(), StatusCode::kOutOfRange);
  assembler.Drop("cts1", 1);
  EXPECT_TRUE(assembler.Add(SplitTempMap(m)[0]).ok());
}

}  // namespace
}  // namespace fleetmap::core
