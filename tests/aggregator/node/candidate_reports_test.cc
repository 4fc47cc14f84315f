// A vehicle's reports on the candidates (candidate_reports.h), driven directly with their
// payloads after one merge made the pallet a candidate: a report that changes cells is a
// version of its own whose delta and candidates go out; a report that cannot be right, or
// whose journal write fails, changes nothing and sends nothing.
#include "aggregator/node/candidate_reports.h"

#include <gtest/gtest.h>

#include "tests/aggregator/node/node_parts_util.h"
#include "tests/aggregator/test_files.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Channels;
using testing::Encode;
using testing::HeldBytes;
using testing::KeyOf;
using testing::NodeParts;
using testing::PalletMaps;
using testing::SeenFreeBytes;
using testing::TileCount;

// The pallet's first map merged (its cells candidates, seen once), then the reports.
struct Reporting {
  explicit Reporting(const std::string& state_dir = "")
      : parts({}, state_dir), reports(parts.aggregator, parts.publisher, parts.report()) {
    const core::TempMap& map = PalletMaps()[0];
    parts.committer.Complete(KeyOf(map), map, TileCount(map), 1.7e9, 1.0);
    for (const auto& [cell, candidate] : parts.aggregator.store().candidates())
      candidates.push_back(static_cast<int32_t>(cell));
    parts.out.sent.clear();
  }
  void GiveSeenFree(const std::string& channel_vehicle, const std::vector<uint8_t>& bytes) {
    reports.OnSeenFree(lcmtypes::CandidatesFreeChannel(channel_vehicle), bytes.data(),
                       static_cast<int>(bytes.size()), 2000.0);
  }
  void GiveHeld(const std::string& channel_vehicle, const std::vector<uint8_t>& bytes) {
    reports.OnHeld(lcmtypes::CandidatesHeldChannel(channel_vehicle), bytes.data(),
                   static_cast<int>(bytes.size()), 2000.0);
  }

  NodeParts parts;
  CandidateReports reports;
  std::vector<int32_t> candidates;
};

TEST(CandidateReportsTest, CandidatesAVehicleSawFreeAreDroppedInAVersionOfTheirOwn) {
  Reporting r;
  ASSERT_GT(r.candidates.size(), 2u);
  // The map that saw them ended at 1010 s: a pass begun after it says they are gone.
  r.GiveSeenFree("v2", SeenFreeBytes("v2", {r.candidates[0], r.candidates[1]}, 1011.0));
  EXPECT_EQ(r.parts.counters.seen_free_reports, 1);
  EXPECT_EQ(r.parts.counters.candidates_dropped, 2);
  EXPECT_EQ(r.parts.aggregator.store().version(), 2u);
  EXPECT_EQ(r.parts.aggregator.store().candidates().size(), r.candidates.size() - 2);
  const std::vector<std::string> channels = Channels(r.parts.out);
  ASSERT_GE(channels.size(), 2u);
  EXPECT_EQ(channels.front(), lcmtypes::kMapDeltaChannel);
  EXPECT_EQ(channels.back(), lcmtypes::kMapCandidatesChannel);
  const auto deltas = r.parts.out.Decoded<fleetmap::map_delta_t>(lcmtypes::kMapDeltaChannel);
  EXPECT_EQ(deltas.front().base_version, 1);
}

TEST(CandidateReportsTest, CandidatesAVehicleSawHeldLongEnoughAreAdded) {
  Reporting r;
  ASSERT_GT(r.candidates.size(), 2u);
  const std::vector<int32_t> two = {r.candidates[0], r.candidates[1]};
  r.GiveHeld("v1", HeldBytes("v1", two, 1002.0, 1008.0));  // not long enough: nothing changes
  EXPECT_EQ(r.parts.aggregator.store().version(), 1u);
  EXPECT_TRUE(r.parts.out.sent.empty());
  r.GiveHeld("v1", HeldBytes("v1", two, 1002.0, 1013.0));
  EXPECT_EQ(r.parts.counters.held_reports, 2);
  EXPECT_EQ(r.parts.counters.candidates_held_added, 2);
  EXPECT_EQ(r.parts.aggregator.store().version(), 2u);
  EXPECT_EQ(r.parts.out.Count(lcmtypes::kMapCandidatesChannel), 1u);
}

TEST(CandidateReportsTest, AReportThatCannotBeRightChangesAndSendsNothing) {
  Reporting r;
  ASSERT_FALSE(r.candidates.empty());
  r.GiveSeenFree("v2", SeenFreeBytes("v3", r.candidates, 1011.0));  // another vehicle's name
  r.GiveHeld("v2", HeldBytes("v3", r.candidates, 1002.0, 1013.0));
  EXPECT_EQ(r.parts.counters.wrong_vehicle_id, 2);
  r.GiveSeenFree("v2", SeenFreeBytes("v2", {r.candidates[0], 1 << 30}, 1011.0));  // outside the map
  r.GiveSeenFree("v2", SeenFreeBytes("v2", {}, 1011.0));
  EXPECT_EQ(r.parts.counters.bad_seen_free, 2);
  EXPECT_EQ(r.parts.lines.Containing("CANDIDATES_FREE_v2: report refused"), 1);
  r.GiveHeld("v1", HeldBytes("v1", {r.candidates[0]}, 1013.0, 1002.0));  // ends before it begins
  EXPECT_EQ(r.parts.counters.bad_held, 1);
  r.GiveSeenFree("v2", {1, 2, 3});
  EXPECT_EQ(r.parts.counters.malformed_messages, 1);
  EXPECT_EQ(r.parts.counters.seen_free_reports + r.parts.counters.held_reports, 0);
  EXPECT_EQ(r.parts.aggregator.store().version(), 1u);
  EXPECT_EQ(r.parts.aggregator.store().candidates().size(), r.candidates.size());
  EXPECT_TRUE(r.parts.out.sent.empty());
}

TEST(CandidateReportsTest, AReportWhoseJournalWriteFailsChangesAndSendsNothing) {
  fleetmap::testing::ScratchFolder folder;
  Reporting r(folder.path());
  ASSERT_GT(r.candidates.size(), 1u);
  {
    aggregator::testing::FileSizeLimit full_disk(16);  // the journal cannot grow
    r.GiveSeenFree("v2", SeenFreeBytes("v2", {r.candidates[0]}, 1011.0));
  }
  EXPECT_EQ(r.parts.counters.seen_free_reports, 1);
  EXPECT_EQ(r.parts.counters.persist_errors, 1);
  EXPECT_EQ(r.parts.counters.candidates_dropped, 0);
  EXPECT_EQ(r.parts.lines.Containing("candidates v2 saw free not dropped"), 1);
  EXPECT_EQ(r.parts.aggregator.store().version(), 1u);
  EXPECT_TRUE(r.parts.out.sent.empty());
}

}  // namespace
}  // namespace fleetmap::aggregator::node
