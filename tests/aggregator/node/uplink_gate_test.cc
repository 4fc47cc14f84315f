// Which uplink messages get in (uplink_gate.h): each channel the aggregator reads is handed
// on by kind; its own acknowledgements, unknown channels, oversize or payloadless messages
// and, with a fleet key, anything not signed by the channel's owner go no further.
#include "aggregator/node/uplink_gate.h"

#include <gtest/gtest.h>

#include "auth/key.h"
#include "auth/signer.h"
#include "lcmtypes/channels.h"
#include "tests/aggregator/node/node_test_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::LogLines;

struct Gate {
  explicit Gate(AggregatorNodeOptions node_options = {})
      : options(std::move(node_options)), log(lines.Sink()), gate(options, {counters, log}) {}
  std::optional<UplinkMessage> Open(const std::string& channel, const std::vector<uint8_t>& m) {
    return gate.Open(channel, m.data(), static_cast<int>(m.size()));
  }

  const AggregatorNodeOptions options;
  LogLines lines;
  NodeCounters counters;
  CauseLog log;
  UplinkGate gate;
};

const std::vector<uint8_t> kPayload = {1, 2, 3, 4};

TEST(UplinkGateTest, EachChannelTheAggregatorReadsIsHandedOnByKindAsItsPayload) {
  Gate g;
  const std::vector<std::pair<std::string, UplinkKind>> channels = {
      {lcmtypes::TempMapChannel("v1"), UplinkKind::kTempMapTile},
      {lcmtypes::CandidatesFreeChannel("v1"), UplinkKind::kCandidatesFree},
      {lcmtypes::CandidatesHeldChannel("v1"), UplinkKind::kCandidatesHeld},
      {lcmtypes::kMapRequestChannel, UplinkKind::kMapRequest}};
  for (const auto& [channel, kind] : channels) {
    const auto m = g.Open(channel, kPayload);
    ASSERT_TRUE(m.has_value()) << channel;
    EXPECT_EQ(m->kind, kind) << channel;
    EXPECT_EQ(m->data, kPayload.data());
    EXPECT_EQ(m->size, 4);
  }
  EXPECT_EQ(g.counters.messages, 4);
  EXPECT_FALSE(g.gate.verifier().enabled());
}

TEST(UplinkGateTest, OurOwnAcknowledgementsAndUnknownChannelsGoNoFurther) {
  Gate g;
  EXPECT_FALSE(g.Open(lcmtypes::kTempMapAckChannel, kPayload).has_value());
  EXPECT_EQ(g.counters.ignored_messages, 1);
  EXPECT_FALSE(g.Open("POSE_v1", kPayload).has_value());
  EXPECT_FALSE(g.Open("POSE_v2", kPayload).has_value());
  EXPECT_EQ(g.counters.unknown_channel, 2);
  EXPECT_EQ(g.lines.Containing("which the aggregator does not read"), 1);
  EXPECT_EQ(g.counters.messages, 3);
}

TEST(UplinkGateTest, OversizeAndPayloadlessMessagesAreRefusedBeforeAnythingElse) {
  AggregatorNodeOptions options;
  options.limits.max_received_bytes = 1024;
  Gate g(options);
  EXPECT_FALSE(g.Open("POSE_v1", std::vector<uint8_t>(2000)).has_value());
  EXPECT_EQ(g.counters.oversize_received, 1);
  EXPECT_EQ(g.counters.unknown_channel, 0);  // refused before its channel was looked at
  EXPECT_FALSE(g.gate.Open(lcmtypes::TempMapChannel("v1"), nullptr, 5).has_value());
  EXPECT_FALSE(g.gate.Open(lcmtypes::TempMapChannel("v1"), kPayload.data(), -1).has_value());
  EXPECT_EQ(g.counters.malformed_messages, 2);
  EXPECT_TRUE(g.Open(lcmtypes::TempMapChannel("v1"), std::vector<uint8_t>(1024)).has_value());
}

TEST(UplinkGateTest, WithAFleetKeyOnlyTheChannelsOwnerGetsInAndAnyMemberMayAsk) {
  AggregatorNodeOptions options;
  options.fleet_key = auth::GenerateKey();
  Gate g(options);
  auth::Signer v1(options.fleet_key, "v1", auth::FirstSequence(1.7e9));
  auth::Signer v2(options.fleet_key, "v2", auth::FirstSequence(1.7e9));
  const std::string channel = lcmtypes::TempMapChannel("v1");
  const auto sealed = [&](auth::Signer& signer, const std::string& on) {
    std::vector<uint8_t> m = kPayload;
    signer.Seal(on, m);
    return m;
  };
  const std::vector<uint8_t> own = sealed(v1, channel);
  const auto m = g.Open(channel, own);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->size, 4);  // the payload, without its trailer
  EXPECT_FALSE(g.Open(channel, sealed(v2, channel)).has_value());
  EXPECT_FALSE(g.Open(channel, kPayload).has_value());
  EXPECT_EQ(g.counters.auth_refused, 2);
  EXPECT_EQ(g.gate.verifier().counters().auth_wrong_sender, 1);
  EXPECT_EQ(g.gate.verifier().counters().auth_unsigned, 1);
  EXPECT_EQ(g.lines.Containing("does not own this channel"), 1);
  EXPECT_TRUE(
      g.Open(lcmtypes::kMapRequestChannel, sealed(v2, lcmtypes::kMapRequestChannel)).has_value());
  EXPECT_TRUE(g.gate.verifier().enabled());
}

}  // namespace
}  // namespace fleetmap::aggregator::node
