#include "core/map/temp_map_file.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/codec/cell_packing.h"
#include "core/codec/map_codec.h"
#include "core/io/byte_io.h"
#include "core/io/crc32.h"

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

TEST(TempMapFileTest, TheAnchorItsCovarianceAndTheGridOriginAreKeptApart) {
  TempMap original = Sample();
  Eigen::Matrix3d c;
  c << 4e-4, 1e-4, 0.0, 1e-4, 9e-4, 2e-5, 0.0, 2e-5, 3e-4;
  original.anchor_covariance = c;
  const auto bytes = EncodeTempMap(original);
  auto back = DecodeTempMap(bytes.data(), bytes.size());
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  // The aggregator turns a map about its anchor, which is the vehicle's pose, not the corner.
  EXPECT_EQ(back->anchor_in_map.x_m, 3.0);
  EXPECT_EQ(back->anchor_in_map.theta_rad, 0.5);
  EXPECT_EQ(back->grid.geometry().origin().x_m, -1.0);
  ASSERT_TRUE(back->anchor_covariance.has_value());
  EXPECT_EQ(*back->anchor_covariance, c);
}

TEST(TempMapFileTest, AFileWithoutCovarianceReadsBackWithout) {
  const auto bytes = EncodeTempMap(Sample());
  auto back = DecodeTempMap(bytes.data(), bytes.size());
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_FALSE(back->anchor_covariance.has_value());
}

// A file as the first version wrote it (an agent's outbox from before the covariance was
// kept): the placed corner, no grid origin, no covariance.
std::vector<uint8_t> FirstVersionFile(const TempMap& m) {
  std::vector<uint8_t> out;
  ByteWriter w(out);
  const uint8_t magic[4] = {'F', 'M', 'T', 'M'};
  w.Bytes(magic, 4);
  w.U8(1);
  w.U32(static_cast<uint32_t>(m.vehicle_id.size()));
  w.Bytes(reinterpret_cast<const uint8_t*>(m.vehicle_id.data()), m.vehicle_id.size());
  w.I32(m.sequence);
  const Pose2 corner = m.PlacedGeometry().origin();
  for (double v : {corner.x_m, corner.y_m, corner.theta_rad, m.grid.geometry().resolution_m(),
                   m.start_s, m.end_s})
    w.F64(v);
  CodecOptions codec;
  codec.packing = CellPacking::kLogOddsInt8;
  const std::vector<uint8_t> frame = EncodeWindow(m.grid, m.grid.geometry().full_window(), codec);
  w.U32(static_cast<uint32_t>(frame.size()));
  w.Bytes(frame.data(), frame.size());
  w.U32(Crc32(out.data(), out.size()));
  return out;
}

TEST(TempMapFileTest, AFileOfTheFirstVersionStillReads) {
  const TempMap original = Sample();
  const auto bytes = FirstVersionFile(original);
  auto back = DecodeTempMap(bytes.data(), bytes.size());
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  const GridGeometry a = original.PlacedGeometry(), b = back->PlacedGeometry();
  EXPECT_NEAR(a.origin().x_m, b.origin().x_m, 1e-12);
  EXPECT_NEAR(a.origin().y_m, b.origin().y_m, 1e-12);
  EXPECT_FALSE(back->anchor_covariance.has_value());
  EXPECT_EQ(back->grid.state({3, 4}), CellState::kOccupied);
}

TEST(TempMapFileTest, AnInvalidCovarianceIsAnError) {
  TempMap m = Sample();
  m.anchor_covariance = Eigen::Matrix3d::Identity() * 1e-4;
  (*m.anchor_covariance)(1, 1) = -1e-4;
  const auto bytes = EncodeTempMap(m);
  EXPECT_FALSE(DecodeTempMap(bytes.data(), bytes.size()).ok());
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
