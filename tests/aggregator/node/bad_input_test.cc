#include <gtest/gtest.h>

#include <random>

#include "aggregator/node/map_hash.h"
#include "tests/aggregator/node/node_test_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::Feed;
using testing::LogLines;
using testing::MakeNode;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;

class AggregatorNodeBadInputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    node_ = MakeNode(&out_, log_.Sink());
    hash_ = MapHash(node_->aggregator().store().current_map());
    tiles_ = TileMessages(PalletMaps()[0], kUtime);
  }
  void Send(const std::string& channel, const std::vector<uint8_t>& bytes) {
    node_->OnMessage(channel, bytes.data(), static_cast<int>(bytes.size()), 1.0);
  }
  fleetmap::tempmap_tile_t Tile(size_t i) const {
    return *lcmtypes::Decode<fleetmap::tempmap_tile_t>(tiles_[i].data(), int(tiles_[i].size()));
  }
  void ExpectMapUnchanged() {
    EXPECT_EQ(node_->aggregator().store().version(), 0u);
    EXPECT_EQ(MapHash(node_->aggregator().store().current_map()), hash_);
    EXPECT_EQ(node_->counters().maps_completed, 0);
  }

  RecordingPublisher out_;
  LogLines log_;
  std::unique_ptr<AggregatorNode> node_;
  uint64_t hash_ = 0;
  std::vector<std::vector<uint8_t>> tiles_;
};

TEST_F(AggregatorNodeBadInputTest, TruncatedAndGarbageTilesAreCountedAndLoggedOnce) {
  std::vector<uint8_t> truncated(tiles_[0].begin(), tiles_[0].begin() + tiles_[0].size() / 2);
  Send("TEMPMAP_v1", truncated);
  Send("TEMPMAP_v1", {});
  Send("TEMPMAP_v1", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12});
  std::vector<uint8_t> trailing = tiles_[0];
  trailing.push_back(0);
  Send("TEMPMAP_v1", trailing);
  node_->OnMessage("TEMPMAP_v1", nullptr, -5, 1.0);
  EXPECT_EQ(node_->counters().malformed_messages, 5);
  EXPECT_EQ(log_.Containing("not a tempmap_tile_t"), 1);
  ExpectMapUnchanged();
}

TEST_F(AggregatorNodeBadInputTest, AnotherTypeOnATempMapChannelIsMalformed) {
  fleetmap::map_request_t request;
  request.utime = kUtime;
  request.vehicle_id = "v1";
  request.have_version = -1;
  request.num_tiles = 0;
  Send("TEMPMAP_v1", Encode(request));
  EXPECT_EQ(node_->counters().malformed_messages, 1);
  EXPECT_EQ(node_->counters().tiles_received, 0);
  ExpectMapUnchanged();
}

TEST_F(AggregatorNodeBadInputTest, ATileOfAnotherVehicleIsRefused) {
  for (const auto& t : tiles_) Send("TEMPMAP_v2", t);  // v1's map on v2's channel
  Send("TEMPMAP_", tiles_[0]);
  EXPECT_EQ(node_->counters().wrong_vehicle_id, static_cast<int64_t>(tiles_.size()) + 1);
  EXPECT_EQ(log_.Containing("refused: a vehicle sends only its own maps"), 1);
  EXPECT_EQ(node_->counters().tiles_received, 0);
  EXPECT_EQ(out_.Count(lcmtypes::kTempMapAckChannel), 0u);
  ExpectMapUnchanged();
}

TEST_F(AggregatorNodeBadInputTest, InvalidAndInconsistentTilesChangeNothing) {
  fleetmap::tempmap_tile_t bad_crc = Tile(0);
  bad_crc.tile.crc32 ^= 1;
  fleetmap::tempmap_tile_t nan_anchor = Tile(0);
  nan_anchor.anchor_pose.x_m = std::nan("");
  Send("TEMPMAP_v1", Encode(bad_crc));
  Send("TEMPMAP_v1", Encode(nan_anchor));
  EXPECT_EQ(node_->counters().invalid_tiles, 2);

  Send("TEMPMAP_v1", tiles_[0]);
  fleetmap::tempmap_tile_t other_size = Tile(1);  // the same map claims another size
  other_size.width_cells += 64;
  Send("TEMPMAP_v1", Encode(other_size));
  fleetmap::tempmap_tile_t huge = Tile(0);  // a map of 4 billion cells
  huge.tempmap_seq = 77;
  huge.width_cells = huge.height_cells = 65536;
  Send("TEMPMAP_v1", Encode(huge));
  fleetmap::tempmap_tile_t index = Tile(2);  // an index outside its count
  index.tile_index = 4000;
  Send("TEMPMAP_v1", Encode(index));
  EXPECT_EQ(node_->counters().inconsistent_tiles, 3);
  EXPECT_EQ(log_.Containing("refused"), 1);  // logged once for the cause
  EXPECT_EQ(node_->incomplete_maps(), 1u);
  ExpectMapUnchanged();
  // The good tiles still make the map.
  for (size_t i = 1; i < tiles_.size(); ++i) Send("TEMPMAP_v1", tiles_[i]);
  EXPECT_EQ(node_->aggregator().store().version(), 1u);
}

TEST_F(AggregatorNodeBadInputTest, GarbageAndImpossibleMapRequestsAreCounted) {
  Send(lcmtypes::kMapRequestChannel, {0xde, 0xad, 0xbe, 0xef});
  Send(lcmtypes::kMapRequestChannel, tiles_[0]);  // another type
  fleetmap::map_request_t request;
  request.utime = kUtime;
  request.vehicle_id = "v1";
  request.have_version = -7;
  request.num_tiles = 0;
  Send(lcmtypes::kMapRequestChannel, Encode(request));
  request.have_version = -1;
  request.tiles = {0, 1'000'000};
  request.num_tiles = 2;
  Send(lcmtypes::kMapRequestChannel, Encode(request));
  request.tiles = {-1};
  request.num_tiles = 1;
  Send(lcmtypes::kMapRequestChannel, Encode(request));
  EXPECT_EQ(node_->counters().malformed_messages, 2);
  EXPECT_EQ(node_->counters().bad_requests, 3);
  EXPECT_EQ(node_->counters().requests, 0);
  node_->Tick(1.0);
  EXPECT_EQ(node_->counters().asked_tiles_sent, 0);
  EXPECT_EQ(log_.Containing("MAP_REQUEST"), 2);  // one line per cause
  ExpectMapUnchanged();
}

TEST_F(AggregatorNodeBadInputTest, UnknownChannelsAndOurOwnAcknowledgementsAreNotTiles) {
  Send("SCAN_v1", tiles_[0]);
  Send("MAP_DELTA", tiles_[0]);
  Send(lcmtypes::kTempMapAckChannel, tiles_[0]);
  EXPECT_EQ(node_->counters().unknown_channel, 2);
  EXPECT_EQ(node_->counters().ignored_messages, 1);
  EXPECT_EQ(node_->counters().tiles_received, 0);
  ExpectMapUnchanged();
}

TEST_F(AggregatorNodeBadInputTest, TooManyIncompleteMapsAreRefusedNotHeld) {
  // Ten vehicles with four maps each (limits.max_pending_maps_per_vehicle): 40 maps.
  for (int32_t seq = 100; seq < 140; ++seq) {
    fleetmap::tempmap_tile_t t = Tile(0);
    t.tempmap_seq = seq;
    t.vehicle_id = "w" + std::to_string((seq - 100) / 4);
    Send(lcmtypes::TempMapChannel(t.vehicle_id), Encode(t));
  }
  EXPECT_EQ(node_->incomplete_maps(), 32u);
  EXPECT_EQ(node_->counters().assembler_full, 8);
  node_->Tick(1.0 + 601.0);  // silent for longer than pending_map_timeout_s
  EXPECT_EQ(node_->incomplete_maps(), 0u);
  EXPECT_EQ(node_->counters().maps_evicted, 32);
  ExpectMapUnchanged();
}

TEST_F(AggregatorNodeBadInputTest, AnAbsurdTileCountOnAFinishedMapIsNotEchoed) {
  for (const auto& t : tiles_) Send("TEMPMAP_v1", t);
  ASSERT_EQ(node_->aggregator().store().version(), 1u);
  fleetmap::tempmap_tile_t resent = Tile(0);
  resent.tile_count = 2'000'000'000;  // no layout check runs for a map already merged
  node_->OnMessage("TEMPMAP_v1", Encode(resent).data(), int(Encode(resent).size()), 5.0);
  const auto acks = out_.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[1].outcome, fleetmap::tempmap_ack_t::DUPLICATE);
  EXPECT_LE(acks[1].num_received, 4096);
  EXPECT_EQ(node_->aggregator().store().version(), 1u);
}

TEST_F(AggregatorNodeBadInputTest, RandomlyCorruptedMessagesNeverCrashOrMerge) {
  std::mt19937 rng(5);
  const std::vector<std::string> channels = {"TEMPMAP_v1", lcmtypes::kMapRequestChannel};
  for (int round = 0; round < 3000; ++round) {
    std::vector<uint8_t> bytes = tiles_[rng() % tiles_.size()];
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bytes[rng() % bytes.size()] ^= uint8_t(1u << (rng() % 8));
    if (rng() % 4 == 0) bytes.resize(rng() % bytes.size());
    Send(channels[rng() % channels.size()], bytes);
    if (round % 100 == 0) node_->Tick(1.0 + round * 0.01);
  }
  const NodeCounters& c = node_->counters();
  EXPECT_EQ(c.messages, 3000);
  EXPECT_GT(c.malformed_messages, 0);
  EXPECT_LE(c.tiles_received, 3000);
  ExpectMapUnchanged();
}

}  // namespace
}  // namespace fleetmap::aggregator::node
