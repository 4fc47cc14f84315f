// The candidate watch at the aggregator's edge: the candidates go out after a merge, a
// vehicle's report of candidates it saw free drops them (a new version, its delta, the new
// set), and a report that cannot be right changes nothing.
#include <gtest/gtest.h>

#include "fleetmap/map_candidates_t.hpp"
#include "tests/aggregator/node/node_test_util.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::Feed;
using testing::HeldBytes;
using testing::MakeNode;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::SeenFreeBytes;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;  // when the vehicle sent its tiles

std::vector<int32_t> SentCandidates(const RecordingPublisher& out) {
  const auto sets = out.Decoded<fleetmap::map_candidates_t>(lcmtypes::kMapCandidatesChannel);
  std::vector<int32_t> cells;
  if (sets.empty()) return cells;
  const int16_t parts = sets.back().parts;
  for (size_t i = sets.size() - static_cast<size_t>(std::max<int16_t>(parts, 1)); i < sets.size();
       ++i)
    cells.insert(cells.end(), sets[i].cells.begin(), sets[i].cells.end());
  return cells;
}

void Give(AggregatorNode& node, const std::string& channel, const std::vector<uint8_t>& bytes) {
  node.OnMessage(channel, bytes.data(), static_cast<int>(bytes.size()), 2000.0);
}

TEST(CandidatesNodeTest, ACandidateAVehicleSawFreeIsDroppedAndTheNewSetSent) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  Feed(*node, "v1", TileMessages(PalletMaps()[0], kUtime), 100.0);
  ASSERT_EQ(node->counters().maps_merged, 1);
  const size_t candidates = node->aggregator().store().candidates().size();
  ASSERT_GT(candidates, 0u);  // the pallet, seen once
  const std::vector<int32_t> sent = SentCandidates(out);
  ASSERT_EQ(sent.size(), candidates);
  const uint64_t version = node->aggregator().store().version();
  const size_t deltas = out.Count(lcmtypes::kMapDeltaChannel);

  // Passes that began before the map that saw them ended (1010 s) say nothing about later.
  Give(*node, lcmtypes::CandidatesFreeChannel("v2"), SeenFreeBytes("v2", sent, 1005.0));
  EXPECT_EQ(node->aggregator().store().candidates().size(), candidates);
  EXPECT_EQ(node->aggregator().store().version(), version);

  Give(*node, lcmtypes::CandidatesFreeChannel("v2"),
       SeenFreeBytes("v2", {sent[0], sent[1]}, 1011.0));
  EXPECT_EQ(node->counters().candidates_dropped, 2);
  EXPECT_EQ(node->aggregator().store().candidates().size(), candidates - 2);
  EXPECT_EQ(node->aggregator().store().version(), version + 1);
  EXPECT_EQ(out.Count(lcmtypes::kMapDeltaChannel), deltas + 1);  // vehicles follow the version
  EXPECT_EQ(SentCandidates(out).size(), candidates - 2);
}

// The vehicle that saw the pallet kept its beams on it for 11 s (1002 to 1013 s, around the
// map that made it a candidate): added in a version of its own, and the vehicles follow.
TEST(CandidatesNodeTest, ACandidateAVehicleSawHeldIsAddedAndTheNewSetSent) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  Feed(*node, "v1", TileMessages(PalletMaps()[0], kUtime), 100.0);
  const std::vector<int32_t> sent = SentCandidates(out);
  ASSERT_GT(sent.size(), 2u);
  const uint64_t version = node->aggregator().store().version();
  const size_t deltas = out.Count(lcmtypes::kMapDeltaChannel);
  const std::string channel = lcmtypes::CandidatesHeldChannel("v1");
  Give(*node, channel, HeldBytes("v1", {sent[0], sent[1]}, 1002.0, 1008.0));  // too short
  EXPECT_EQ(node->aggregator().store().version(), version);
  Give(*node, channel, HeldBytes("v1", {sent[0], sent[1]}, 1002.0, 1013.0));
  EXPECT_EQ(node->counters().held_reports, 2);
  EXPECT_EQ(node->counters().candidates_held_added, 2);
  EXPECT_EQ(node->aggregator().store().version(), version + 1);
  EXPECT_TRUE(node->aggregator().store().semi_static()[static_cast<size_t>(sent[0])]);
  EXPECT_EQ(out.Count(lcmtypes::kMapDeltaChannel), deltas + 1);
  EXPECT_EQ(SentCandidates(out).size(), sent.size() - 2);
  // Impossible reports: another vehicle's name, a hold that ends before it begins.
  Give(*node, channel, HeldBytes("v2", {sent[2]}, 1002.0, 1013.0));
  EXPECT_EQ(node->counters().wrong_vehicle_id, 1);
  Give(*node, channel, HeldBytes("v1", {sent[2]}, 1013.0, 1002.0));
  EXPECT_EQ(node->counters().bad_held, 1);
  EXPECT_EQ(node->counters().candidates_held_added, 2);
}

TEST(CandidatesNodeTest, AReportThatCannotBeRightIsRefusedAndCounted) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  Feed(*node, "v1", TileMessages(PalletMaps()[0], kUtime), 100.0);
  const std::vector<int32_t> sent = SentCandidates(out);
  ASSERT_FALSE(sent.empty());
  const size_t candidates = sent.size();
  // Another vehicle's name on v2's channel, a cell outside the map, no cells, garbage.
  Give(*node, lcmtypes::CandidatesFreeChannel("v2"), SeenFreeBytes("v3", sent, 1011.0));
  EXPECT_EQ(node->counters().wrong_vehicle_id, 1);
  Give(*node, lcmtypes::CandidatesFreeChannel("v2"),
       SeenFreeBytes("v2", {sent[0], 1 << 30}, 1011.0));
  Give(*node, lcmtypes::CandidatesFreeChannel("v2"), SeenFreeBytes("v2", {}, 1011.0));
  EXPECT_EQ(node->counters().bad_seen_free, 2);
  const std::vector<uint8_t> garbage = {1, 2, 3};
  Give(*node, lcmtypes::CandidatesFreeChannel("v2"), garbage);
  EXPECT_EQ(node->counters().malformed_messages, 1);
  EXPECT_EQ(node->counters().candidates_dropped, 0);
  EXPECT_EQ(node->aggregator().store().candidates().size(), candidates);
}

}  // namespace
}  // namespace fleetmap::aggregator::node
