// The committer (map_committer.h) driven directly with complete maps: what a merge and a
// rejection send and in which order, the merge rate's held maps, a map with no room to be
// held, the journal failing, and the record of finished maps.
#include "aggregator/node/map_committer.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/aggregator/node/node_parts_util.h"
#include "tests/aggregator/test_files.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Channels;
using testing::KeyOf;
using testing::NodeParts;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::TileCount;

constexpr double kStampS = 1.7e9;  // the completing tiles' stamps, 1 s apart

void Complete(NodeParts& parts, size_t i, double now_s) {
  const core::TempMap& map = PalletMaps()[i];
  parts.committer.Complete(KeyOf(map), map, TileCount(map), kStampS + static_cast<double>(i),
                           now_s);
}

std::vector<int32_t> MergedSequences(const RecordingPublisher& out) {
  std::vector<int32_t> merged;
  for (const auto& a : out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel))
    if (a.outcome == fleetmap::tempmap_ack_t::MERGED) merged.push_back(a.tempmap_seq);
  return merged;
}

AggregatorNodeOptions SlowMerges() {
  AggregatorNodeOptions options;
  options.limits.merges_per_min = 6.0;  // one per 10 s of the maps' stamps
  options.limits.merge_burst = 1.0;
  return options;
}

TEST(MapCommitterTest, AMergeIsAcknowledgedThenReportedThenItsDeltaAndCandidatesGoOut) {
  NodeParts parts;
  const core::TempMap& map = PalletMaps()[0];
  Complete(parts, 0, 1.0);
  EXPECT_EQ(parts.aggregator.store().version(), 1u);
  EXPECT_EQ(parts.counters.maps_merged, 1);
  const std::vector<std::string> channels = Channels(parts.out);
  ASSERT_GE(channels.size(), 4u);
  EXPECT_EQ(channels[0], lcmtypes::kTempMapAckChannel);
  EXPECT_EQ(channels[1], lcmtypes::kMergeReportChannel);
  EXPECT_EQ(channels[2], lcmtypes::kMapDeltaChannel);
  EXPECT_EQ(channels.back(), lcmtypes::kMapCandidatesChannel);
  const auto acks = parts.out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::MERGED);
  EXPECT_EQ(acks[0].map_version, 1);
  EXPECT_EQ(acks[0].num_received, TileCount(map));
  const auto reports = parts.out.Decoded<fleetmap::merge_report_t>(lcmtypes::kMergeReportChannel);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_TRUE(reports[0].accepted);
  EXPECT_EQ(reports[0].utime, lcmtypes::ToUtime(kStampS));  // the map's stamp, not the clock
  const auto handled = parts.committer.Handled(KeyOf(map));
  ASSERT_TRUE(handled.has_value());
  EXPECT_TRUE(handled->merged);
  EXPECT_EQ(handled->version, 1u);
}

TEST(MapCommitterTest, ARejectionIsAcknowledgedWithItsReasonAndSendsNoDelta) {
  NodeParts parts;
  core::TempMap far = PalletMaps()[0];
  far.sequence = 9;
  far.anchor_in_map = core::Pose2(far.anchor_in_map.x_m + 30.0, far.anchor_in_map.y_m, 0.0);
  parts.committer.Complete(KeyOf(far), far, TileCount(far), kStampS, 1.0);
  EXPECT_EQ(Channels(parts.out), (std::vector<std::string>{lcmtypes::kTempMapAckChannel,
                                                           lcmtypes::kMergeReportChannel}));
  const auto acks = parts.out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].outcome, fleetmap::tempmap_ack_t::REJECTED);
  EXPECT_FALSE(acks[0].reason.empty());
  EXPECT_EQ(parts.counters.maps_rejected, 1);
  const auto handled = parts.committer.Handled(KeyOf(far));
  ASSERT_TRUE(handled.has_value());
  EXPECT_FALSE(handled->merged);
  EXPECT_EQ(parts.aggregator.store().version(), 0u);
}

TEST(MapCommitterTest, AMapsKeptTilesLeaveTheSpoolOnceItsOutcomeIsJournaled) {
  fleetmap::testing::ScratchFolder folder;
  AggregatorNodeOptions options;
  options.spool_dir = folder.File("incoming");
  NodeParts parts(options);
  const MapKey key = KeyOf(PalletMaps()[0]);
  ASSERT_TRUE(parts.spool.Save(key, 0, {1, 2, 3}).ok());
  Complete(parts, 0, 1.0);
  EXPECT_FALSE(parts.spool.Has(key, 0));
  EXPECT_TRUE(std::filesystem::is_empty(options.spool_dir));
}

TEST(MapCommitterTest, MapsOverTheMergeRateAreHeldAndMergedInOrderAsItAllows) {
  NodeParts parts(SlowMerges());
  for (size_t i = 0; i < 3; ++i) Complete(parts, i, 1.0 + static_cast<double>(i));
  EXPECT_EQ(MergedSequences(parts.out), (std::vector<int32_t>{1}));
  EXPECT_EQ(parts.counters.throttled_merges, 2);
  EXPECT_EQ(parts.committer.held_maps(), 2);
  // A resend of a held map is the committer's: nothing to assemble, nothing merged.
  EXPECT_TRUE(parts.committer.OnResend(KeyOf(PalletMaps()[1]), kStampS + 1, 5.0));
  EXPECT_EQ(parts.counters.duplicates, 1);
  parts.committer.Tick(6.0);  // half a map's worth of time
  EXPECT_EQ(MergedSequences(parts.out), (std::vector<int32_t>{1}));
  parts.committer.Tick(12.0);
  EXPECT_EQ(MergedSequences(parts.out), (std::vector<int32_t>{1, 2}));
  parts.committer.Tick(22.0);
  EXPECT_EQ(MergedSequences(parts.out), (std::vector<int32_t>{1, 2, 3}));
  EXPECT_EQ(parts.committer.held_maps(), 0);
}

TEST(MapCommitterTest, AMapWithNoRoomToBeHeldWaitsUnacknowledgedForItsResend) {
  AggregatorNodeOptions options = SlowMerges();
  options.max_held_maps = 1;
  NodeParts parts(options);
  for (size_t i = 0; i < 3; ++i) Complete(parts, i, 1.0 + static_cast<double>(i));
  const MapKey third = KeyOf(PalletMaps()[2]);
  EXPECT_EQ(parts.committer.held_maps(), 1);
  EXPECT_FALSE(parts.committer.Handled(third).has_value());
  EXPECT_EQ(parts.lines.Containing("waits unacknowledged for a resend"), 1);
  EXPECT_TRUE(parts.committer.OnResend(third, kStampS + 2, 4.0));  // the second still waits
  EXPECT_EQ(parts.counters.throttled_merges, 3);
  EXPECT_EQ(parts.lines.Containing("waits unacknowledged for a resend"), 1);  // once per cause
  parts.committer.Tick(12.0);
  EXPECT_EQ(MergedSequences(parts.out), (std::vector<int32_t>{1, 2}));
  EXPECT_TRUE(parts.committer.OnResend(third, kStampS + 2, 40.0));
  EXPECT_EQ(MergedSequences(parts.out), (std::vector<int32_t>{1, 2, 3}));
  EXPECT_FALSE(parts.committer.OnResend({"v1", 77}, kStampS, 41.0));  // not the committer's
}

TEST(MapCommitterTest, MapsTheJournalRefusedWaitUnacknowledgedAndMergeInArrivalOrder) {
  fleetmap::testing::ScratchFolder folder;
  NodeParts parts({}, folder.path());
  {
    aggregator::testing::FileSizeLimit full_disk(16);  // the journal cannot grow
    Complete(parts, 0, 1.0);
  }
  EXPECT_TRUE(parts.committer.persist_failed());
  EXPECT_EQ(parts.counters.persist_errors, 1);
  Complete(parts, 1, 1.2);  // the disk has room, but the map waits behind the first
  EXPECT_EQ(parts.committer.unjournaled_maps(), 2u);
  EXPECT_TRUE(parts.out.sent.empty());
  EXPECT_EQ(parts.aggregator.store().version(), 0u);
  parts.committer.Tick(1.5);  // before the next try
  EXPECT_EQ(parts.committer.unjournaled_maps(), 2u);
  parts.committer.Tick(1.0 + MapCommitter::kPersistRetryS);
  EXPECT_EQ(MergedSequences(parts.out), (std::vector<int32_t>{1, 2}));
  EXPECT_FALSE(parts.committer.persist_failed());
  EXPECT_EQ(parts.committer.unjournaled_maps(), 0u);
  EXPECT_EQ(parts.lines.Containing("not journaled, not acknowledged"), 1);
}

TEST(MapCommitterTest, EveryMergeOfTheCurrentMapsHistoryIsKnownToANewCommitter) {
  NodeParts parts;
  Complete(parts, 0, 1.0);
  MapCommitter again(parts.aggregator, parts.options, parts.spool, parts.limits, parts.publisher,
                     parts.report());
  const auto handled = again.Handled(KeyOf(PalletMaps()[0]));
  ASSERT_TRUE(handled.has_value());
  EXPECT_TRUE(handled->merged);
  EXPECT_EQ(handled->version, 1u);
  EXPECT_FALSE(again.Handled({"v1", 77}).has_value());
}

}  // namespace
}  // namespace fleetmap::aggregator::node
