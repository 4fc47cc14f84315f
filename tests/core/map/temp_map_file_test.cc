#include "core/map/temp_map_file.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/codec/cell_packing.h"

namespace fleetmap::core {
namespace {

TempMap Sample() {
  TempMap m;
  m.vehicle_id = "cts2";
  m.sequence = 41;
  m.anchor_in_map = Pose2(3.0, 4.0, 0.5);
  m.grid = OccupancyGrid(GridGeometry(0.05, 70, 30, Pose2(-1.0, -0.5, 0)));
  m.grid.SetState({3, 4}, CellState::kOccupied);
  m.grid.SetLogOdds({10, 10}, -1.2f);
  m.start_s = 5.0;
  m.end_s = 9.0;
  return m;
}

TEST(TempMapFileTest, RoundTripKeepsPlacementAndEvidence) {
  const TempMap original = Sample();
  const auto bytes = EncodeTempMap(original);
  auto back = DecodeTempMap(bytes.data(), bytes.size());
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->vehicle_id, "cts2");
  EXPECT_EQ(back->sequence, 41);
  const GridGeometry a = original.PlacedGeometry(), b = back->PlacedGeometry();
  EXPECT_DOUBLE_EQ(a.origin().x_m, b.origin().x_m);
  EXPECT_DOUBLE_EQ(a.origin().theta_rad, b.origin().theta_rad);
  EXPECT_EQ(back->grid.state({3, 4}), CellState::kOccupied);
  EXPECT_NEAR(back->grid.log_odds({10, 10}), -1.2f, kLogOddsQuantum);
  EXPECT_EQ(back->end_s, 9.0);
}

TEST(TempMapFileTest, EveryCorruptionIsAnError) {
  const auto bytes = EncodeTempMap(Sample());
  for (size_t n = 0; n < bytes.size(); n += 7) {
    ASSERT_FALSE(DecodeTempMap(bytes.data(), n).ok()) << "truncated at " << n;
  }
  for (size_t i = 0; i < bytes.size(); i += 5) {
    auto flipped = bytes;
    flipped[i] ^= 0x40;
    ASSERT_FALSE(DecodeTempMap(flipped.data(), flipped.size()).ok()) << "byte " << i;
  }
}

TEST(TempMapFileTest, SaveAndLoad) {
  const std::string dir = ::testing::TempDir() + "/temp_map_file_test";
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(SaveTempMap(Sample(), dir + "/m.fmtm").ok());
  auto back = LoadTempMap(dir + "/m.fmtm");
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->sequence, 41);
  EXPECT_EQ(LoadTempMap(dir + "/missing.fmtm").status().code(), StatusCode::kNotFound);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fleetmap::core
