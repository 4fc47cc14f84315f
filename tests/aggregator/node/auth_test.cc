// The aggregator node with a fleet key (docs/security.md): signed temporary maps merge, and
// what it sends is signed; unsigned, forged, replayed and wrong-sender tiles are refused,
// counted by cause and logged once; without a key STATUS says "not authenticated".
#include <gtest/gtest.h>

#include "auth/signer.h"
#include "auth/trailer.h"
#include "auth/verifier.h"
#include "tests/aggregator/node/node_test_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Feed;
using testing::LogLines;
using testing::MakeNode;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::SentMessage;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;

std::vector<std::vector<uint8_t>> Signed(std::vector<std::vector<uint8_t>> messages,
                                         auth::Signer& signer, const std::string& channel) {
  for (auto& m : messages) signer.Seal(channel, m);
  return messages;
}

// What the node sent on `channel`, checked as a vehicle holding `key` would, then decoded.
template <typename T>
std::vector<T> Verified(const RecordingPublisher& out, const std::string& channel,
                        const auth::Key& key) {
  auth::Verifier verifier(key);
  std::vector<T> decoded;
  for (const SentMessage& m : out.sent) {
    if (m.channel != channel) continue;
    auth::Opened opened;
    EXPECT_EQ(verifier.Open(m.channel, m.bytes.data(), static_cast<int>(m.bytes.size()),
                            "aggregator", &opened),
              auth::Verdict::kAccepted)
        << channel;
    auto msg = lcmtypes::Decode<T>(opened.data, opened.size);
    EXPECT_TRUE(msg.ok()) << msg.status().ToString();
    if (msg.ok()) decoded.push_back(*msg);
  }
  return decoded;
}

int64_t StatusCounter(const fleetmap::status_t& s, const std::string& name) {
  for (size_t i = 0; i < s.counter_names.size(); ++i)
    if (s.counter_names[i] == name) return s.counter_values[i];
  return -1;
}

struct KeyedNode {
  auth::Key key = auth::GenerateKey();
  RecordingPublisher out;
  LogLines log;
  std::unique_ptr<AggregatorNode> node;
  KeyedNode() {
    AggregatorNodeOptions options;
    options.fleet_key = key;
    node = MakeNode(&out, log.Sink(), "", options);
  }
};

TEST(AggregatorAuthTest, SignedTilesMergeAndEverythingSentIsSigned) {
  KeyedNode k;
  auth::Signer v1(k.key, "v1", auth::FirstSequence(1.7e9));
  Feed(*k.node, "v1", Signed(TileMessages(PalletMaps()[0], kUtime), v1, "TEMPMAP_v1"), 1.0);
  k.node->Tick(1.5);
  EXPECT_EQ(k.node->aggregator().store().version(), 1u);
  const auto acks = Verified<fleetmap::tempmap_ack_t>(k.out, lcmtypes::kTempMapAckChannel, k.key);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_FALSE(Verified<fleetmap::map_delta_t>(k.out, lcmtypes::kMapDeltaChannel, k.key).empty());
  EXPECT_EQ(Verified<fleetmap::merge_report_t>(k.out, lcmtypes::kMergeReportChannel, k.key).size(),
            1u);
  const auto status = Verified<fleetmap::status_t>(k.out, "STATUS_aggregator", k.key);
  ASSERT_FALSE(status.empty());
  EXPECT_TRUE(status.back().authenticated);
  EXPECT_EQ(StatusCounter(status.back(), "auth_verified"),
            static_cast<int64_t>(TileMessages(PalletMaps()[0], kUtime).size()));
  // A receiver that holds another fleet's key believes none of it.
  auth::Verifier stranger(auth::GenerateKey());
  for (const SentMessage& m : k.out.sent) {
    auth::Opened o;
    EXPECT_EQ(stranger.Open(m.channel, m.bytes.data(), int(m.bytes.size()), "aggregator", &o),
              auth::Verdict::kForged);
  }
}

TEST(AggregatorAuthTest, ForgedReplayedWrongSenderAndUnsignedTilesAreRefusedAndCounted) {
  KeyedNode k;
  const auto tiles = TileMessages(PalletMaps()[0], kUtime);
  const int64_t n = static_cast<int64_t>(tiles.size());

  // Forged: v1's tiles signed with a key that is not the fleet's.
  auth::Signer forger(auth::GenerateKey(), "v1", auth::FirstSequence(1.7e9));
  Feed(*k.node, "v1", Signed(tiles, forger, "TEMPMAP_v1"), 1.0);
  // On VEHICLE_A's channel, signed by VEHICLE_B (a real member with its own key).
  auth::Signer v2(k.key, "v2", auth::FirstSequence(1.7e9));
  Feed(*k.node, "v1", Signed(tiles, v2, "TEMPMAP_v1"), 1.1);
  // Unsigned.
  Feed(*k.node, "v1", tiles, 1.2);
  k.node->Tick(1.3);
  EXPECT_EQ(k.node->aggregator().store().version(), 0u);
  EXPECT_EQ(k.node->counters().tiles_received, 0);
  EXPECT_EQ(k.out.Count(lcmtypes::kTempMapAckChannel), 0u);

  // Valid, then the same bytes replayed: merged once, the replay never reaches the map code
  // (no DUPLICATE answer either).
  auth::Signer v1(k.key, "v1", auth::FirstSequence(1.7e9));
  const auto valid = Signed(tiles, v1, "TEMPMAP_v1");
  Feed(*k.node, "v1", valid, 2.0);
  Feed(*k.node, "v1", valid, 3.0);
  k.node->Tick(3.5);
  EXPECT_EQ(k.node->aggregator().store().version(), 1u);
  EXPECT_EQ(k.node->counters().duplicates, 0);
  EXPECT_EQ(k.out.Count(lcmtypes::kTempMapAckChannel), 1u);

  const auth::AuthCounters& a = k.node->auth_counters();
  EXPECT_EQ(a.auth_forged, n);
  EXPECT_EQ(a.auth_wrong_sender, n);
  EXPECT_EQ(a.auth_unsigned, n);
  EXPECT_EQ(a.auth_replayed, n);
  EXPECT_EQ(a.auth_verified, n);
  EXPECT_EQ(k.node->counters().auth_refused, 4 * n);
  const auto status = Verified<fleetmap::status_t>(k.out, "STATUS_aggregator", k.key);
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(StatusCounter(status.back(), "auth_forged"), n);
  EXPECT_EQ(StatusCounter(status.back(), "auth_wrong_sender"), n);
  EXPECT_EQ(StatusCounter(status.back(), "auth_unsigned"), n);
  EXPECT_EQ(StatusCounter(status.back(), "auth_replayed"), n);
  // One log line per cause, however many messages.
  EXPECT_EQ(k.log.Containing("MAC is wrong"), 1);
  EXPECT_EQ(k.log.Containing("does not own this channel"), 1);
  EXPECT_EQ(k.log.Containing("unsigned message"), 1);
  EXPECT_EQ(k.log.Containing("replayed message"), 1);
}

TEST(AggregatorAuthTest, ARequestMustBeSignedByAMemberOfTheFleet) {
  KeyedNode k;
  fleetmap::map_request_t r;
  r.vehicle_id = "v1";
  r.have_version = -1;
  r.num_tiles = 0;
  auto bytes = testing::Encode(r);
  k.node->OnMessage(lcmtypes::kMapRequestChannel, bytes.data(), int(bytes.size()), 1.0);
  EXPECT_EQ(k.node->counters().requests, 0);
  auth::Signer v1(k.key, "v1", auth::FirstSequence(1.7e9));
  v1.Seal(lcmtypes::kMapRequestChannel, bytes);
  k.node->OnMessage(lcmtypes::kMapRequestChannel, bytes.data(), int(bytes.size()), 1.0);
  EXPECT_EQ(k.node->counters().requests, 1);
  EXPECT_EQ(k.node->auth_counters().auth_unsigned, 1);
}

TEST(AggregatorAuthTest, WithoutAKeyNothingIsSignedAndStatusSaysSo) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  // A signed map from a keyed vehicle still merges: the trailer is split off unchecked.
  auth::Signer v1(auth::GenerateKey(), "v1", 1);
  Feed(*node, "v1", Signed(TileMessages(PalletMaps()[0], kUtime), v1, "TEMPMAP_v1"), 1.0);
  node->Tick(1.5);
  EXPECT_EQ(node->aggregator().store().version(), 1u);
  EXPECT_FALSE(node->authenticated());
  EXPECT_GT(node->auth_counters().auth_unverified, 0);
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_aggregator");  // plain LCM
  ASSERT_FALSE(status.empty());
  EXPECT_FALSE(status.back().authenticated);
}

}  // namespace
}  // namespace fleetmap::aggregator::node
