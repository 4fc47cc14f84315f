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

core::Result<core::TempMap> ThroughTheWire(const core::TempMap& original) {
  core::TempMapAssembler assembler;
  for (const core::TempMapTile& t : core::SplitTempMap(original)) {
    auto back = FromMessage(ThroughBytes(ToMessage(t, 42)));
    if (!back.ok()) return back.status();
    auto done = assembler.Add(*back);
    if (!done.ok()) return done.status();
    if (done->has_value()) return **done;
  }
  return core::DataLoss("the map was not completed");
}

TEST(TransportConvertTest, TheAnchorsCovarianceTravelsWithTheMap) {
  core::TempMap original = Sample();
  Eigen::Matrix3d c;
  c << 4e-4, 1e-4, 2e-5, 1e-4, 9e-4, -3e-5, 2e-5, -3e-5, 3e-4;
  original.anchor_covariance = c;
  auto done = ThroughTheWire(original);
  ASSERT_TRUE(done.ok()) << done.status().ToString();
  ASSERT_TRUE(done->anchor_covariance.has_value());
  EXPECT_EQ(*done->anchor_covariance, c);  // doubles on the wire: exactly
}

TEST(TransportConvertTest, AMapWithoutCovarianceArrivesWithoutOne) {
  auto done = ThroughTheWire(Sample());
  ASSERT_TRUE(done.ok()) << done.status().ToString();
  EXPECT_FALSE(done->anchor_covariance.has_value());
}

TEST(TransportConvertTest, ACovarianceThatCannotBeOneIsRefused) {
  const auto tiles = core::SplitTempMap(Sample());
  auto msg = ToMessage(tiles[0], 1);
  msg.has_anchor_covariance = true;
  for (int i = 0; i < 9; ++i) msg.anchor_covariance[i] = i % 4 ? 0.0 : 1e-4;
  EXPECT_TRUE(FromMessage(msg).ok());
  msg.anchor_covariance[4] = -1e-4;  // a negative variance
  EXPECT_EQ(FromMessage(msg).status().code(), core::StatusCode::kInvalidArgument);
  msg.anchor_covariance[4] = 1e-4;
  msg.anchor_covariance[1] = 5e-4;  // not symmetric
  EXPECT_FALSE(FromMessage(msg).ok());
  msg.anchor_covariance[3] = 5e-4;  // symmetric, but a correlation of 5
  EXPECT_FALSE(FromMessage(msg).ok());
  msg.anchor_covariance[1] = msg.anchor_covariance[3] = 0.0;
  msg.anchor_covariance[8] = NAN;
  EXPECT_FALSE(FromMessage(msg).ok());
}

TEST(TransportConvertTest, TilesOfOneMapMustAgreeOnTheCovariance) {
  core::TempMap original = Sample();
  original.grid = core::OccupancyGrid(core::GridGeometry(0.05, 200, 80, core::Pose2(-2, -2, 0)));
  const auto tiles = core::SplitTempMap(original);
  ASSERT_GE(tiles.size(), 2u);
  core::TempMapAssembler assembler;
  ASSERT_TRUE(assembler.Add(tiles[0]).ok());
  core::TempMapTile other = tiles[1];
  other.anchor_covariance = Eigen::Matrix3d::Identity() * 1e-4;
  EXPECT_FALSE(assembler.Add(other).ok());
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
