// Bounds per vehicle (vehicle_limits.h): a vehicle that floods is throttled, counted and
// logged once, while another vehicle's temporary map is still merged.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/aggregator/node/node_test_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Feed;
using testing::LogLines;
using testing::MakeNode;
using testing::PalletMap;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;

TEST(AggregatorLimitsTest, AFloodingVehicleIsThrottledWhileAnotherIsMerged) {
  RecordingPublisher out;
  LogLines log;
  auto node = MakeNode(&out, log.Sink());
  // v9 floods: 60 temporary maps, all but the last tile of each (so none completes), the
  // same second; v1 sends one map in the middle of it.
  core::TempMap flood = PalletMaps()[1];
  flood.vehicle_id = "v9";
  const auto v1_tiles = TileMessages(PalletMaps()[0], kUtime);
  int64_t flood_tiles = 0;
  for (int32_t seq = 1; seq <= 60; ++seq) {
    flood.sequence = seq;
    auto tiles = TileMessages(flood, kUtime);
    tiles.pop_back();
    Feed(*node, "v9", tiles, 1.0 + seq * 0.001);
    flood_tiles += static_cast<int64_t>(tiles.size());
    if (seq == 30) Feed(*node, "v1", v1_tiles, 1.03);
  }
  node->Tick(1.5);

  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  int v1_merged = 0;
  for (const auto& a : acks)
    v1_merged += a.vehicle_id == "v1" && a.outcome == fleetmap::tempmap_ack_t::MERGED;
  EXPECT_EQ(v1_merged, 1);
  EXPECT_EQ(node->aggregator().store().version(), 1u);

  const NodeCounters& c = node->counters();
  std::printf(
      "flood: %lld tiles of v9 in 60 ms: throttled_tiles %lld, vehicle_maps_full %lld; "
      "v1 merged %d\n",
      (long long)flood_tiles, (long long)c.throttled_tiles, (long long)c.vehicle_maps_full,
      v1_merged);
  const VehicleLimitOptions limits;
  EXPECT_GT(c.throttled_tiles, 0);  // over tiles_per_s after a burst of tile_burst
  EXPECT_LE(c.throttled_tiles, flood_tiles - static_cast<int64_t>(limits.tile_burst) + 1);
  EXPECT_GT(c.vehicle_maps_full, 0);  // more incomplete maps of v9 than it may have
  // v9's, up to its limit; v1's map completed.
  EXPECT_EQ(node->incomplete_maps(), static_cast<size_t>(limits.max_pending_maps_per_vehicle));
  EXPECT_EQ(node->throttled_vehicles(), 1);
  EXPECT_EQ(log.Containing("'v9' sends more than"), 1);
  EXPECT_EQ(log.Containing("'v1'"), 0);
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_aggregator");
  ASSERT_FALSE(status.empty());
  const auto& names = status.back().counter_names;
  for (const char* name : {"throttled_tiles", "vehicle_maps_full", "throttled_vehicles",
                           "throttled_merges", "oversize_received"})
    EXPECT_EQ(std::count(names.begin(), names.end(), name), 1) << name;
}

AggregatorNodeOptions SlowMerges() {
  AggregatorNodeOptions options;
  options.limits.merges_per_min = 6.0;  // one per 10 s of the maps' stamps
  options.limits.merge_burst = 1.0;
  return options;
}

std::vector<int32_t> AckedSequences(const RecordingPublisher& out) {
  std::vector<int32_t> merged;
  for (const auto& a : out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel))
    if (a.outcome == fleetmap::tempmap_ack_t::MERGED) merged.push_back(a.tempmap_seq);
  return merged;
}

// Maps made faster than the rate (stamps 1 s apart) are held, and merged in the vehicle's
// order as the rate allows, without waiting for a resend (a replay never resends).
TEST(AggregatorLimitsTest, MergesOverAVehiclesRateAreHeldAndMergedInOrder) {
  RecordingPublisher out;
  auto node = MakeNode(&out, {}, "", SlowMerges());
  for (int i = 0; i < 3; ++i)
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + i * 1'000'000), 1.0 + i);
  EXPECT_EQ(AckedSequences(out), (std::vector<int32_t>{1}));
  EXPECT_EQ(node->counters().throttled_merges, 2);
  Feed(*node, "v1", {TileMessages(PalletMaps()[1], kUtime + 1'000'000).back()}, 5.0);
  EXPECT_EQ(node->counters().duplicates, 1);  // a resend of a held map changes nothing
  node->Tick(6.0);
  EXPECT_EQ(AckedSequences(out), (std::vector<int32_t>{1}));  // 0.5 maps' worth of time
  node->Tick(12.0);
  EXPECT_EQ(AckedSequences(out), (std::vector<int32_t>{1, 2}));
  node->Tick(22.0);
  EXPECT_EQ(AckedSequences(out), (std::vector<int32_t>{1, 2, 3}));
}

// An uplink log replayed 20 times faster than it was recorded: the stamps keep the rate.
TEST(AggregatorLimitsTest, AReplayFasterThanRealIsMergedAsItWasMade) {
  RecordingPublisher out;
  auto node = MakeNode(&out, {}, "", SlowMerges());
  for (int i = 0; i < 4; ++i)
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + i * 20'000'000), 1.0 + i);
  EXPECT_EQ(node->counters().throttled_merges, 0);
  EXPECT_EQ(AckedSequences(out), (std::vector<int32_t>{1, 2, 3, 4}));
}

// Stamps that run ahead of the host's clock by more than max_replay_speed (forged, or a
// backlog sent at once) refill the rate only that much faster than real time.
TEST(AggregatorLimitsTest, StampsFarAheadOfTheClockDoNotLiftTheRate) {
  RecordingPublisher out;
  auto node = MakeNode(&out, {}, "", SlowMerges());
  for (int i = 0; i < 4; ++i)
    Feed(*node, "v1", TileMessages(PalletMaps()[i], kUtime + i * 1000'000'000LL), 1.0 + i * 0.1);
  EXPECT_EQ(AckedSequences(out), (std::vector<int32_t>{1}));
  EXPECT_EQ(node->counters().throttled_merges, 3);
}

TEST(AggregatorLimitsTest, AnOversizeMessageIsRefusedBeforeDecoding) {
  RecordingPublisher out;
  LogLines log;
  auto node = MakeNode(&out, log.Sink());
  const std::vector<uint8_t> big(70'000, 0x55);
  for (int i = 0; i < 3; ++i)
    node->OnMessage("TEMPMAP_v1", big.data(), static_cast<int>(big.size()), 1.0);
  EXPECT_EQ(node->counters().oversize_received, 3);
  EXPECT_EQ(node->counters().malformed_messages, 0);
  EXPECT_EQ(log.Containing("70000 bytes refused"), 1);
}

TEST(AggregatorLimitsTest, BadLimitsAreRefused) {
  AggregatorNodeOptions o;
  o.limits.tiles_per_s = 0;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.limits.max_pending_maps_per_vehicle = 0;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.limits.max_received_bytes = 10;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.limits.max_replay_speed = 0.5;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.max_held_maps = 0;
  EXPECT_FALSE(o.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::aggregator::node
