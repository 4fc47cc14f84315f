// The aggregator node's downlink (map_publisher.h): what each message says, that everything
// sent is signed, that sizes and transport failures are counted and logged once, and that
// without a Publisher nothing is sent or counted.
#include "aggregator/node/map_publisher.h"

#include <gtest/gtest.h>

#include "auth/key.h"
#include "auth/verifier.h"
#include "tests/aggregator/node/node_parts_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::NodeParts;
using testing::Received;
using testing::RecordingPublisher;

class RefusingPublisher : public Publisher {
 public:
  bool Publish(Link, const std::string&, const std::vector<uint8_t>&) override { return false; }
};

TEST(MapPublisherTest, APendingAcknowledgementNamesTheTilesGivenAndTheCurrentVersion) {
  NodeParts parts;
  parts.publisher.SendPendingAck({"v1", 4}, 5, {0, 2}, 3.0);
  const auto acks = parts.out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].vehicle_id, "v1");
  EXPECT_EQ(acks[0].tempmap_seq, 4);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::PENDING);
  EXPECT_EQ(acks[0].tile_count, 5);
  EXPECT_EQ(Received(acks[0]), (std::vector<int32_t>{0, 2}));
  EXPECT_EQ(acks[0].map_version, 0);
  EXPECT_EQ(acks[0].utime, lcmtypes::ToUtime(3.0));
  EXPECT_EQ(parts.counters.pending_acks_sent, 1);
  EXPECT_EQ(parts.counters.acks_sent, 1);
  EXPECT_EQ(parts.publisher.largest_messages().at(lcmtypes::kTempMapAckChannel),
            parts.out.sent[0].bytes.size());
}

TEST(MapPublisherTest, AFinalAcknowledgementNamesEveryTileOfACountClampedToTheBound) {
  AggregatorNodeOptions options;
  options.assembler.max_tiles = 8;
  NodeParts parts(options);
  parts.publisher.SendFinalAck({"v1", 1}, 1'000'000, fleetmap::tempmap_ack_t::DUPLICATE, "", 7,
                               1.0);
  parts.publisher.SendFinalAck({"v1", 2}, -3, fleetmap::tempmap_ack_t::REJECTED, "too far", 7, 1.0);
  const auto acks = parts.out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].tile_count, 8);
  EXPECT_EQ(Received(acks[0]), (std::vector<int32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(acks[0].map_version, 7);
  EXPECT_EQ(acks[1].tile_count, 0);
  EXPECT_TRUE(acks[1].received_tiles.empty());
  EXPECT_EQ(acks[1].reason, "too far");
  EXPECT_EQ(parts.counters.acks_sent, 2);
  EXPECT_EQ(parts.counters.pending_acks_sent, 0);
}

TEST(MapPublisherTest, AKeyframeIsEveryTileOrOnlyTheTilesOfTheMapAskedFor) {
  NodeParts parts;
  parts.publisher.SendKeyframe(nullptr, 1.0);
  const size_t all = parts.out.Count(lcmtypes::kMapKeyframeChannel);
  ASSERT_GT(all, 1u);
  const std::vector<int32_t> only = {3, 1 << 20};  // the second is no tile of the map
  parts.publisher.SendKeyframe(&only, 2.0);
  const auto keyframes = parts.out.Decoded<fleetmap::map_keyframe_t>(lcmtypes::kMapKeyframeChannel);
  ASSERT_EQ(keyframes.size(), all + 1);
  EXPECT_EQ(keyframes.back().tile_index, 3);
  EXPECT_EQ(keyframes.back().tile_count, static_cast<int32_t>(all));
  EXPECT_EQ(parts.counters.keyframe_tiles_sent, static_cast<int64_t>(all + 1));
}

TEST(MapPublisherTest, WithAFleetKeyEverythingSentIsSignedAsTheProcess) {
  AggregatorNodeOptions options;
  options.fleet_key = auth::GenerateKey();
  NodeParts parts(options);
  parts.publisher.SendCandidates(1.0);
  parts.publisher.SendDelta(MapDelta{}, 1.0);
  ASSERT_EQ(parts.out.sent.size(), 2u);
  auth::Verifier vehicle(options.fleet_key);
  for (const auto& m : parts.out.sent) {
    auth::Opened opened;
    EXPECT_EQ(vehicle.Open(m.channel, m.bytes.data(), static_cast<int>(m.bytes.size()),
                           options.process_name, &opened),
              auth::Verdict::kAccepted)
        << m.channel;
  }
}

TEST(MapPublisherTest, AMessageOverTheSizeBoundIsStillSentButCountedAndLoggedOnce) {
  AggregatorNodeOptions options;
  options.max_message_bytes = 1024;
  NodeParts parts(options);
  StatusFields status;
  status.process = options.process_name;
  for (int i = 0; i < 200; ++i) status.counters.emplace_back("counter_" + std::to_string(i), i);
  parts.publisher.SendStatus(status, 1.0);
  parts.publisher.SendStatus(status, 2.0);
  EXPECT_EQ(parts.out.Count("STATUS_aggregator"), 2u);
  EXPECT_EQ(parts.counters.oversize_messages, 2);
  EXPECT_EQ(parts.lines.Containing("one lost packet loses it"), 1);
  EXPECT_GT(parts.publisher.largest_messages().at("STATUS_aggregator"), 1024u);
}

TEST(MapPublisherTest, WhatTheTransportRefusesIsCountedAndLoggedOnce) {
  NodeParts parts;
  RefusingPublisher refusing;
  MapPublisher publisher(parts.aggregator, parts.options, &refusing, parts.report());
  publisher.SendCandidates(1.0);
  publisher.SendCandidates(2.0);
  EXPECT_EQ(parts.counters.publish_failures, 2);
  EXPECT_EQ(parts.lines.Containing("refused a message on MAP_CANDIDATES"), 1);
  EXPECT_EQ(parts.counters.candidate_sets_sent, 2);
}

TEST(MapPublisherTest, WithoutAPublisherNothingIsSentOrCounted) {
  NodeParts parts({}, "", /*publishing=*/false);
  EXPECT_FALSE(parts.publisher.enabled());
  parts.publisher.SendPendingAck({"v1", 1}, 3, {0}, 1.0);
  parts.publisher.SendFinalAck({"v1", 1}, 3, fleetmap::tempmap_ack_t::MERGED, "", 1, 1.0);
  parts.publisher.SendMergeReport(MergeReport{}, core::Pose2(), 1.0);
  parts.publisher.SendDelta(MapDelta{}, 1.0);
  parts.publisher.SendKeyframe(nullptr, 1.0);
  parts.publisher.SendCandidates(1.0);
  parts.publisher.SendStatus(StatusFields{}, 1.0);
  EXPECT_TRUE(parts.out.sent.empty());
  EXPECT_TRUE(parts.publisher.largest_messages().empty());
  const NodeCounters& c = parts.counters;
  for (int64_t n : {c.acks_sent, c.pending_acks_sent, c.merge_reports_sent, c.delta_tiles_sent,
                    c.keyframe_tiles_sent, c.candidate_sets_sent})
    EXPECT_EQ(n, 0);
}

}  // namespace
}  // namespace fleetmap::aggregator::node
