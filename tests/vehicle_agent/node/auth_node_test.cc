// The agent node with a fleet key (docs/security.md): everything it sends is signed as its
// vehicle id; downlink messages count only when the aggregator signed them. And the keyed
// pair end to end, in memory: the agent's temporary map reaches a keyed aggregator, merges,
// and the agent applies the new version.
#include <gtest/gtest.h>

#include <deque>

#include "aggregator/node/aggregator_node.h"
#include "auth/signer.h"
#include "auth/verifier.h"
#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

std::unique_ptr<AgentNode> MakeKeyedNode(const sim::World& world, const auth::Key& key,
                                         RecordingPublisher* out) {
  AgentNodeOptions options = testing::RoomOptions(world);
  options.fleet_key = key;
  auto node = AgentNode::Create(options, out, nullptr, world.static_map(), 0.0);
  EXPECT_TRUE(node.ok()) << node.status().ToString();
  return std::move(node).value();
}

TEST(AgentAuthTest, EverythingSentIsSignedAsTheVehicle) {
  const sim::World world = testing::RoomWorld();
  const auth::Key key = auth::GenerateKey();
  RecordingPublisher out;
  auto node = MakeKeyedNode(world, key, &out);
  testing::DriveNode(world, *node, 3.0);
  auth::Verifier aggregator_side(key);
  ASSERT_GT(out.sent.size(), 50u);
  for (const testing::SentMessage& m : out.sent) {
    auth::Opened o;
    ASSERT_EQ(aggregator_side.Open(m.channel, m.bytes.data(), int(m.bytes.size()), "v1", &o),
              auth::Verdict::kAccepted)
        << m.channel;
  }
  EXPECT_TRUE(node->authenticated());
  EXPECT_EQ(testing::Counter(*node, "auth_verified"), 0);  // nothing came in yet
}

TEST(AgentAuthTest, DownlinkMessagesNotSignedByTheAggregatorAreRefusedAndCounted) {
  const sim::World world = testing::RoomWorld();
  const auth::Key key = auth::GenerateKey();
  RecordingPublisher out;
  auto node = MakeKeyedNode(world, key, &out);
  const auto keyframe = testing::KeyframeMessages(world.static_map(), 1);
  const auto feed = [&](const std::vector<std::vector<uint8_t>>& messages) {
    for (const auto& m : messages) testing::Feed(*node, Link::kDownlink, "MAP_KEYFRAME", m, 1.0);
  };
  const auto signed_by = [&](auth::Signer& signer) {
    std::vector<std::vector<uint8_t>> out_messages;
    for (const auto& k : keyframe) {
      auto bytes = Encode(k);
      signer.Seal("MAP_KEYFRAME", bytes);
      out_messages.push_back(bytes);
    }
    return out_messages;
  };
  std::vector<std::vector<uint8_t>> plain;
  for (const auto& k : keyframe) plain.push_back(Encode(k));
  auth::Signer forger(auth::GenerateKey(), "aggregator", 1);
  auth::Signer other_vehicle(key, "v2", 1);  // a member, but not the aggregator
  auth::Signer aggregator(key, "aggregator", 1);
  const auto valid = signed_by(aggregator);
  feed(plain);
  feed(signed_by(forger));
  feed(signed_by(other_vehicle));
  EXPECT_EQ(testing::Counter(*node, "keyframe_tiles"), 0);
  feed(valid);
  const int64_t n = static_cast<int64_t>(keyframe.size());
  EXPECT_EQ(testing::Counter(*node, "keyframe_tiles"), n);
  feed(valid);  // replayed
  EXPECT_EQ(testing::Counter(*node, "keyframe_tiles"), n);
  EXPECT_EQ(testing::Counter(*node, "auth_unsigned"), n);
  EXPECT_EQ(testing::Counter(*node, "auth_forged"), n);
  EXPECT_EQ(testing::Counter(*node, "auth_wrong_sender"), n);
  EXPECT_EQ(testing::Counter(*node, "auth_replayed"), n);
  EXPECT_EQ(testing::Counter(*node, "auth_verified"), n);
  EXPECT_EQ(testing::Counter(*node, "auth_refused"), 4 * n);
}

// Both nodes in memory, joined by queues (a message is delivered after the sender's tick, as
// the network would, never from inside it). The agent sends on the uplink, the aggregator on
// the downlink.
class Wire : public Publisher {
 public:
  bool Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) override {
    if (link == Link::kUplink) up.push_back({channel, bytes});
    if (link == Link::kDownlink) down.push_back({channel, bytes});
    return true;
  }
  std::deque<std::pair<std::string, std::vector<uint8_t>>> up, down;
};

TEST(AgentAuthTest, AKeyedAgentAndAKeyedAggregatorMergeEndToEnd) {
  const sim::World world = testing::RoomWorld(testing::kPallet);
  const auth::Key key = auth::GenerateKey();
  Wire wire;
  AgentNodeOptions options = testing::RoomOptions(world);
  options.fleet_key = key;
  auto agent = AgentNode::Create(options, &wire, nullptr, world.static_map(), 0.0);
  ASSERT_TRUE(agent.ok()) << agent.status().ToString();
  aggregator::node::AggregatorNodeOptions aggregator_options;
  aggregator_options.fleet_key = key;
  auto store = aggregator::Aggregator::Create(world.static_map(), aggregator::AggregatorOptions());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  auto server = aggregator::node::AggregatorNode::Create(std::move(store).value(),
                                                         aggregator_options, &wire, {}, 0.0);
  ASSERT_TRUE(server.ok()) << server.status().ToString();
  int acks_to_agent = 0;
  const auto exchange = [&](double t) {
    for (; !wire.up.empty(); wire.up.pop_front()) {
      const auto& [channel, bytes] = wire.up.front();
      (*server)->OnMessage(channel, bytes.data(), static_cast<int>(bytes.size()), t);
    }
    (*server)->Tick(t);
    for (; !wire.down.empty(); wire.down.pop_front()) {
      const auto& [channel, bytes] = wire.down.front();
      acks_to_agent += channel == lcmtypes::kTempMapAckChannel;
      (*agent)->OnMessage(Link::kDownlink, channel, bytes.data(), static_cast<int>(bytes.size()),
                          t);
    }
  };
  testing::DriveNode(world, **agent, 16.0, exchange);
  (*agent)->Shutdown(16.0);
  for (double t = 16.0; t < 40.0; t += 0.5) {
    (*agent)->Tick(t);
    exchange(t);
  }
  EXPECT_GT((*server)->auth_counters().auth_verified, 0);
  EXPECT_EQ((*server)->counters().auth_refused, 0);
  EXPECT_EQ(testing::Counter(**agent, "auth_refused"), 0);
  EXPECT_GT(acks_to_agent, 0);
  // The temporary map was answered: merged (the pallet is new) and applied by the agent.
  EXPECT_GE((*server)->counters().maps_merged, 1)
      << "rejected: " << (*server)->counters().maps_rejected;
  EXPECT_GE(testing::Counter(**agent, "maps_merged"), 1);
  EXPECT_EQ((*agent)->map_version(),
            static_cast<int32_t>((*server)->aggregator().store().version()));
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
