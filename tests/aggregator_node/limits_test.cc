// Bounds per vehicle (vehicle_limits.h): a vehicle that floods is throttled, counted and
// logged once, while another vehicle's temporary map is still merged.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/aggregator_node/node_test_util.h"

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

TEST(AggregatorLimitsTest, MergesOverAVehiclesRateWaitForTheResend) {
  RecordingPublisher out;
  AggregatorNodeOptions options;
  options.limits.merges_per_min = 6.0;  // one per 10 s
  options.limits.merge_burst = 1.0;
  auto node = MakeNode(&out, {}, "", options);
  const auto first = TileMessages(PalletMaps()[0], kUtime);
  const auto second = TileMessages(PalletMaps()[1], kUtime + 20'000'000);
  Feed(*node, "v1", first, 1.0);
  Feed(*node, "v1", second, 2.0);  // complete, but v1 merged 1 s ago
  EXPECT_EQ(node->aggregator().store().version(), 1u);
  EXPECT_EQ(node->counters().throttled_merges, 1);
  Feed(*node, "v1", {second.back()}, 5.0);  // the vehicle's resend, still too early
  EXPECT_EQ(node->aggregator().store().version(), 1u);
  Feed(*node, "v1", {second.back()}, 12.0);  // the rate allows it now
  EXPECT_EQ(node->aggregator().store().version(), 2u);
  const auto acks = out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[1].tempmap_seq, 2);
  EXPECT_EQ(acks[1].outcome, fleetmap::tempmap_ack_t::MERGED);
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
}

}  // namespace
}  // namespace fleetmap::aggregator::node
