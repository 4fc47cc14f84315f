// Inputs on which the fuzz targets (fuzz/, docs/fuzzing.md) found core decoders crashing or
// misbehaving, rebuilt by hand; tests/data/fuzz/<target>/ holds the fuzzers' own inputs, which
// every fuzz run replays. Fixed in core/codec/temp_map_tiles.cc, core/map/map_replica.cc and
// core/yaml_reader.{h,cc}.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/codec/temp_map_tiles.h"
#include "core/io/yaml_reader.h"
#include "core/map/map_replica.h"
#include "tests/core/map/keyframe_tiles.h"

namespace fleetmap::core {
namespace {

using ::testing::HasSubstr;

// 150 x 90 cells: 3 x 2 tiles of 64.
std::vector<TempMapTile> TempMapTiles() {
  TempMap m;
  m.vehicle_id = "cts1";
  m.anchor_in_map = Pose2(12.0, 4.0, 0.3);
  m.grid = OccupancyGrid(GridGeometry(0.05, 150, 90));
  m.start_s = 100.0;
  m.end_s = 112.5;
  return SplitTempMap(m);
}

// 150 x 100 cells: 3 x 2 tiles of 64.
OccupancyGrid Hall() {
  OccupancyGrid g(GridGeometry(0.05, 150, 100, Pose2(1, 2, 0)));
  for (int x = 0; x < 150; ++x) g.SetState({x, 0}, CellState::kOccupied);
  return g;
}

using testing::Keyframe;

// A delta from `base` whose one tile (a valid frame with a valid CRC) holds the window of
// tile (0, 0) but says it is tile (1, 0): it decodes, and cannot be applied.
DeltaTile MisplacedDelta(const OccupancyGrid& g, int32_t base) {
  OccupancyGrid changed = g;
  changed.SetState({5, 5}, CellState::kOccupied);
  const auto tiles = EncodeChangedTiles(g, changed);
  return {base, 0, 1, TileIndex{1, 0}, tiles.at(0).frame};
}

// TileLayout::Linear(row * tiles_x + column) ran on the tile position from the message before
// the position was checked against the layout: a row of 2^30 overflowed int (UBSan).
TEST(CoreFuzzRegressionTest, TilePositionsFarOutsideTheLayoutAreRefused) {
  std::vector<TempMapTile> tiles = TempMapTiles();
  TempMapAssembler assembler;
  TempMapTile far = tiles[0];
  far.tile = {0, 1 << 30};
  EXPECT_THAT(assembler.Add(far).status().message(), HasSubstr("position"));
  // A negative column whose linear index happens to match (1 * 3 - 1 = 2) is refused too.
  TempMapTile negative = tiles[2];
  negative.tile = {-1, 1};
  EXPECT_THAT(assembler.Add(negative).status().message(), HasSubstr("position"));

  std::vector<KeyframeTile> key = Keyframe(Hall(), 1);
  key[0].tile = {1 << 30, 1 << 30};
  MapReplica replica;
  EXPECT_EQ(replica.AddKeyframeTile(key[0]).status().code(), StatusCode::kDataLoss);
}

// A delta that decodes but does not fit the map drops the map (a keyframe is requested); the
// replica still said true ("a version was applied"), and callers then read a map it no longer
// had (fuzz/lcm_map_delta_fuzz.cc, map_replica_fuzz.cc).
TEST(CoreFuzzRegressionTest, DeltaThatDropsTheMapIsNotReportedAsApplied) {
  const OccupancyGrid v1 = Hall();
  MapReplica replica;
  for (const KeyframeTile& t : Keyframe(v1, 1)) ASSERT_TRUE(replica.AddKeyframeTile(t).ok());
  ASSERT_EQ(replica.version(), 1);
  auto applied = replica.AddDeltaTile(MisplacedDelta(v1, 1));
  ASSERT_TRUE(applied.ok());
  EXPECT_FALSE(*applied);
  EXPECT_FALSE(replica.has_map());
  EXPECT_TRUE(replica.NeedsKeyframe());
}

TEST(CoreFuzzRegressionTest, KeyframeDroppedByABufferedDeltaIsNotReportedAsTheMap) {
  const OccupancyGrid v1 = Hall();
  MapReplica replica;
  ASSERT_TRUE(replica.AddDeltaTile(MisplacedDelta(v1, 1)).ok());  // waits for version 1
  const std::vector<KeyframeTile> key = Keyframe(v1, 1);
  Result<bool> done = false;
  for (const KeyframeTile& t : key) done = replica.AddKeyframeTile(t);
  ASSERT_TRUE(done.ok());
  EXPECT_FALSE(*done);
  EXPECT_FALSE(replica.has_map());
}

// yaml-cpp gives an invalid node for a key looked up in a node that lacks it (rect["center"]
// of "rect:" with no value), and throws on every question to it but IsDefined(): Points,
// Numbers, Number, Get and Error let that exception escape (fuzz/scenario_fuzz.cc).
TEST(CoreFuzzRegressionTest, LookupsInMissingNodesReadAsMissing) {
  auto reader = YamlReader::FromString("rect:\nlist: [1, 2]\n", "test.yaml");
  ASSERT_TRUE(reader.ok());
  const YAML::Node rect = reader->root()["rect"];  // null
  const YAML::Node center = rect["center"];        // invalid
  EXPECT_THAT(reader->Points(center, "rect.center", 2).status().message(),
              HasSubstr("rect.center"));
  EXPECT_FALSE(reader->Point(center, "rect.center").ok());
  EXPECT_FALSE(reader->Number(center, "x", "rect.center.x").ok());
  EXPECT_EQ(*reader->Number(center, "x", "rect.center.x", 2.5), 2.5);
  EXPECT_FALSE(reader->Get<std::string>(center, "id", "rect.center.id").ok());
  EXPECT_EQ(*reader->GetOr<int>(center, "n", "rect.center.n", 3), 3);
  EXPECT_THAT(reader->Error(center, "rect.center", "is odd").message(), HasSubstr("is odd"));
}

}  // namespace
}  // namespace fleetmap::core
