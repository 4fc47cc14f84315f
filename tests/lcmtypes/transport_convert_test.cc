#include "lcmtypes/transport_convert.h"

#include <gtest/gtest.h>

#include "lcmtypes/convert.h"

namespace fleetmap::lcmtypes {
namespace {

template <typename T>
T ThroughBytes(const T& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return Decode<T>(buf.data(), static_cast<int>(buf.size())).value();
}

core::TempMap Sample() {
  core::TempMap m;
  m.vehicle_id = "cts1";
  m.sequence = 3;
  m.anchor_in_map = core::Pose2(10, 5, 0.2);
  m.grid = core::OccupancyGrid(core::GridGeometry(0.05, 100, 80, core::Pose2(-2, -2, 0)));
  m.grid.SetState({7, 7}, core::CellState::kOccupied);
  m.start_s = 1000.5;
  m.end_s = 1010.25;
  return m;
}

TEST(TransportConvertTest, TempMapSurvivesTheWire) {
  const core::TempMap original = Sample();
  core::TempMapAssembler assembler;
  std::optional<core::TempMap> done;
  for (const core::TempMapTile& t : core::SplitTempMap(original)) {
    auto back = FromMessage(ThroughBytes(ToMessage(t, 42)));
    ASSERT_TRUE(back.ok()) << back.status().ToString();
    EXPECT_EQ(back->resolution_m, 0.05);  // snapped back from float exactly
    auto r = assembler.Add(*back);
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    if (r->has_value()) done = **r;
  }
  ASSERT_TRUE(done.has_value());
  const core::GridGeometry placed = done->PlacedGeometry();
  EXPECT_NEAR(placed.origin().x_m, original.PlacedGeometry().origin().x_m, 1e-12);
  EXPECT_EQ(done->grid.state({7, 7}), core::CellState::kOccupied);
  EXPECT_NEAR(done->end_s, 1010.25, 1e-6);
}

TEST(TransportConvertTest, CorruptPayloadAndSizesAreRefused) {
  const auto tiles = core::SplitTempMap(Sample());
  auto msg = ToMessage(tiles[0], 1);
  msg.tile.payload[10] ^= 1;
  EXPECT_EQ(FromMessage(msg).status().code(), core::StatusCode::kDataLoss);
  msg = ToMessage(tiles[0], 1);
  msg.anchor_pose.x_m = NAN;
  EXPECT_FALSE(FromMessage(msg).ok());
  msg = ToMessage(tiles[0], 1);
  msg.vehicle_id = "";
  EXPECT_FALSE(FromMessage(msg).ok());
}

TEST(TransportConvertTest, KeyframeAndDeltaTilesFeedAReplica) {
  core::OccupancyGrid v1(core::GridGeometry(0.05, 100, 70, core::Pose2(1, 1, 0)));
  core::OccupancyGrid v2 = v1;
  v2.SetState({50, 50}, core::CellState::kOccupied);
  core::MapReplica replica;
  const auto key = core::EncodeAllTiles(v1);
  for (size_t i = 0; i < key.size(); ++i) {
    const core::KeyframeTile k{
        1, v1.geometry(), 64, int32_t(i), int32_t(key.size()), key[i].index, key[i].frame};
    auto back = FromMessage(ThroughBytes(ToMessage(k, 5)));
    ASSERT_TRUE(back.ok()) << back.status().ToString();
    ASSERT_TRUE(replica.AddKeyframeTile(*back).ok());
  }
  ASSERT_EQ(replica.version(), 1);
  const auto delta = core::EncodeChangedTiles(v1, v2);
  ASSERT_EQ(delta.size(), 1u);
  auto back = FromMessage(
      ThroughBytes(ToMessage(core::DeltaTile{1, 0, 1, delta[0].index, delta[0].frame}, 6)));
  ASSERT_TRUE(back.ok());
  ASSERT_TRUE(replica.AddDeltaTile(*back).ok());
  EXPECT_EQ(replica.version(), 2);
  EXPECT_EQ(replica.map().state({50, 50}), core::CellState::kOccupied);
  auto bad = ToMessage(core::DeltaTile{1, 0, 1, delta[0].index, delta[0].frame}, 6);
  bad.new_version = 5;
  EXPECT_FALSE(FromMessage(bad).ok());
}

}  // namespace
}  // namespace fleetmap::lcmtypes
