// The receiving side of temporary maps (temp_map_receiver.h) driven directly with tile
// messages: assembly in any order, PENDING acknowledgements naming only tiles on disk, what is
// refused before it costs a vehicle's rate, duplicates of finished maps, the bounds on
// incomplete maps, dropping silent maps, and the spool after a restart.
#include "aggregator/node/temp_map_receiver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "tests/aggregator/node/node_parts_util.h"
#include "tests/aggregator/test_files.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::KeyOf;
using testing::NodeParts;
using testing::PalletMaps;
using testing::Received;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;  // when the vehicle sent its tiles

using Messages = std::vector<std::vector<uint8_t>>;

struct Receiving {
  explicit Receiving(AggregatorNodeOptions options = {})
      : parts(std::move(options)),
        receiver(parts.options, parts.spool, parts.limits, parts.committer, parts.publisher,
                 parts.report()) {}
  // Every message on TEMPMAP_<vehicle> at `now_s`.
  void Give(const std::string& vehicle, const Messages& messages, double now_s) {
    for (const auto& m : messages)
      receiver.OnTile(lcmtypes::TempMapChannel(vehicle), m.data(), static_cast<int>(m.size()),
                      now_s);
  }
  std::vector<fleetmap::tempmap_ack_t> Acks() const {
    return parts.out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  }

  NodeParts parts;
  TempMapReceiver receiver;
};

std::vector<int32_t> FirstTiles(size_t n) {
  std::vector<int32_t> tiles(n);
  for (size_t i = 0; i < n; ++i) tiles[i] = static_cast<int32_t>(i);
  return tiles;
}

AggregatorNodeOptions Spooled(const fleetmap::testing::ScratchFolder& folder) {
  AggregatorNodeOptions options;
  options.spool_dir = folder.File("incoming");
  return options;
}

// The first tile of a map of `vehicle` numbered `sequence` (the tile's check covers its cells
// only, so the names can be changed).
std::vector<uint8_t> FirstTileOf(const std::string& vehicle, int32_t sequence) {
  const auto bytes = TileMessages(PalletMaps()[0], kUtime).front();
  auto tile = lcmtypes::Decode<fleetmap::tempmap_tile_t>(bytes.data(), int(bytes.size()));
  EXPECT_TRUE(tile.ok());
  tile->vehicle_id = vehicle;
  tile->tempmap_seq = sequence;
  return Encode(*tile);
}

TEST(TempMapReceiverTest, TilesInAnyOrderBecomeOneMapAndARepeatIsAnsweredAtOnce) {
  Receiving r;
  const Messages tiles = TileMessages(PalletMaps()[0], kUtime);
  r.Give("v1", {tiles[0], tiles[0]}, 1.0);  // the vehicle missed an acknowledgement
  Messages rest(tiles.begin() + 1, tiles.end());
  std::reverse(rest.begin(), rest.end());
  r.Give("v1", rest, 1.1);
  const auto acks = r.Acks();
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::PENDING);
  EXPECT_EQ(Received(acks[0]), (std::vector<int32_t>{0}));
  EXPECT_EQ(acks[1].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_EQ(r.parts.counters.tiles_received, static_cast<int64_t>(tiles.size()) + 1);
  EXPECT_EQ(r.parts.counters.tiles_repeated, 1);
  EXPECT_EQ(r.parts.counters.maps_completed, 1);
  EXPECT_EQ(r.receiver.incomplete_maps(), 0u);
  ASSERT_TRUE(r.parts.committer.Handled(KeyOf(PalletMaps()[0])).has_value());
}

TEST(TempMapReceiverTest, APendingAcknowledgementNamesOnlyTilesKeptOnDisk) {
  fleetmap::testing::ScratchFolder folder;
  Receiving r(Spooled(folder));
  const Messages tiles = TileMessages(PalletMaps()[0], kUtime);
  const Messages all_but_last(tiles.begin(), tiles.end() - 1);
  r.Give("v1", all_but_last, 1.0);
  {
    aggregator::testing::FileSizeLimit full_disk(16);  // no tile fits on disk
    r.receiver.Tick(1.5);
  }
  auto acks = r.Acks();
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_TRUE(acks[0].received_tiles.empty());
  EXPECT_EQ(r.parts.counters.spool_errors, static_cast<int64_t>(all_but_last.size()));
  EXPECT_EQ(r.parts.lines.Containing("cannot keep a received tile on disk"), 1);
  r.Give("v1", {tiles[0]}, 2.1);  // resent: the acknowledgement named nothing
  acks = r.Acks();
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(Received(acks[1]), FirstTiles(all_but_last.size()));
  const MapKey key = KeyOf(PalletMaps()[0]);
  for (int32_t i : Received(acks[1])) EXPECT_TRUE(r.parts.spool.Has(key, i)) << i;
  EXPECT_EQ(r.receiver.incomplete_maps(), 1u);
}

TEST(TempMapReceiverTest, BrokenOrForeignTilesGoNoFurtherAndUseNoneOfTheVehiclesRate) {
  AggregatorNodeOptions options;
  options.limits.tiles_per_s = 1.0;
  options.limits.tile_burst = 1.0;
  Receiving r(options);
  const Messages theirs = TileMessages(testing::PalletMap(0, "v2"), kUtime);
  r.Give("v1", {theirs[0]}, 1.0);
  const std::vector<uint8_t> garbage = {1, 2, 3};
  r.Give("v1", {garbage}, 1.0);
  EXPECT_EQ(r.parts.counters.wrong_vehicle_id, 1);
  EXPECT_EQ(r.parts.counters.malformed_messages, 1);
  const Messages tiles = TileMessages(PalletMaps()[0], kUtime);
  r.Give("v1", {tiles[0], tiles[1], tiles[2]}, 1.0);  // the burst is one tile
  EXPECT_EQ(r.parts.counters.tiles_received, 1);
  EXPECT_EQ(r.parts.counters.throttled_tiles, 2);
  EXPECT_EQ(r.parts.lines.Containing("'v1' sends more than"), 1);
  EXPECT_EQ(r.parts.limits.throttled_vehicles(), 1);
}

TEST(TempMapReceiverTest, AResendOfAFinishedMapIsAnsweredDuplicateAtMostOncePerInterval) {
  Receiving r;
  const Messages tiles = TileMessages(PalletMaps()[0], kUtime);
  r.Give("v1", tiles, 1.0);
  ASSERT_EQ(r.Acks().size(), 1u);  // MERGED
  r.Give("v1", tiles, 3.0);
  r.Give("v1", tiles, 3.2);
  EXPECT_EQ(r.parts.counters.duplicates, 2 * static_cast<int64_t>(tiles.size()));
  auto acks = r.Acks();
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[1].outcome, fleetmap::tempmap_ack_t::DUPLICATE);
  EXPECT_EQ(acks[1].map_version, 1);
  r.Give("v1", {tiles[0]}, 3.6);
  EXPECT_EQ(r.Acks().size(), 3u);
  EXPECT_EQ(r.parts.aggregator.store().version(), 1u);
}

TEST(TempMapReceiverTest, NewMapsBeyondTheVehiclesOrTheNodesBoundWaitForTheirResend) {
  AggregatorNodeOptions options;
  options.limits.max_pending_maps_per_vehicle = 2;
  options.assembler.max_pending_maps = 3;
  Receiving r(options);
  for (int32_t seq = 1; seq <= 3; ++seq) r.Give("v1", {FirstTileOf("v1", seq)}, 1.0);
  EXPECT_EQ(r.parts.counters.vehicle_maps_full, 1);
  for (int32_t seq = 1; seq <= 2; ++seq) r.Give("v2", {FirstTileOf("v2", seq)}, 1.0);
  EXPECT_EQ(r.parts.counters.assembler_full, 1);
  EXPECT_EQ(r.receiver.incomplete_maps(), 3u);
  r.Give("v1", {FirstTileOf("v1", 1)}, 1.1);  // a map already being received still is
  EXPECT_EQ(r.parts.counters.tiles_repeated, 1);
}

TEST(TempMapReceiverTest, AMapSilentForTheTimeoutIsDroppedWithItsKeptTiles) {
  fleetmap::testing::ScratchFolder folder;
  AggregatorNodeOptions options = Spooled(folder);
  options.pending_map_timeout_s = 10.0;
  Receiving r(options);
  const Messages tiles = TileMessages(PalletMaps()[0], kUtime);
  r.Give("v1", Messages(tiles.begin(), tiles.end() - 1), 1.0);
  r.receiver.Tick(1.5);
  ASSERT_FALSE(std::filesystem::is_empty(options.spool_dir));
  r.receiver.Tick(10.9);
  EXPECT_EQ(r.receiver.incomplete_maps(), 1u);
  r.receiver.Tick(11.0);
  EXPECT_EQ(r.receiver.incomplete_maps(), 0u);
  EXPECT_EQ(r.parts.counters.maps_evicted, 1);
  EXPECT_TRUE(std::filesystem::is_empty(options.spool_dir));
  EXPECT_EQ(r.parts.lines.Containing("dropping incomplete temporary map v1#1"), 1);
}

TEST(TempMapReceiverTest, KeptTilesComeBackAfterARestartAndTheMapCompletes) {
  fleetmap::testing::ScratchFolder folder;
  const Messages tiles = TileMessages(PalletMaps()[0], kUtime);
  {
    Receiving before(Spooled(folder));
    before.Give("v1", Messages(tiles.begin(), tiles.end() - 1), 1.0);
    before.receiver.Tick(1.5);
    ASSERT_EQ(before.Acks().size(), 1u);
  }
  Receiving r(Spooled(folder));
  r.receiver.RestoreSpool(2.0);
  EXPECT_EQ(r.receiver.incomplete_maps(), 1u);
  EXPECT_TRUE(r.parts.out.sent.empty());  // nothing new to acknowledge
  EXPECT_EQ(r.parts.lines.Containing("restored " + std::to_string(tiles.size() - 1)), 1);
  r.Give("v1", {tiles.back()}, 2.5);
  const auto acks = r.Acks();
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_TRUE(std::filesystem::is_empty(folder.File("incoming")));
}

TEST(TempMapReceiverTest, AMapWithAnUnreadableKeptTileIsDroppedAtTheRestart) {
  fleetmap::testing::ScratchFolder folder;
  const Messages tiles = TileMessages(PalletMaps()[0], kUtime);
  {
    Receiving before(Spooled(folder));
    before.Give("v1", Messages(tiles.begin(), tiles.end() - 1), 1.0);
    before.receiver.Tick(1.5);
  }
  // Tile 0 of v1#1 ("v1" is 7631 in hex), overwritten with bytes that are no tile.
  std::ofstream(folder.File("incoming/7631.1.0.tile"), std::ios::trunc) << "garbage";
  Receiving r(Spooled(folder));
  r.receiver.RestoreSpool(2.0);
  EXPECT_EQ(r.receiver.incomplete_maps(), 0u);
  EXPECT_EQ(r.parts.counters.spool_errors, 1);
  EXPECT_EQ(r.parts.lines.Containing("tile spool: dropping v1#1"), 1);
  EXPECT_TRUE(std::filesystem::is_empty(folder.File("incoming")));
}

}  // namespace
}  // namespace fleetmap::aggregator::node
