#include "vehicle_agent/tempmap_outbox.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fleetmap::vehicle_agent {
namespace {

core::TempMap Map(int32_t sequence) {
  core::TempMap m;
  m.vehicle_id = "v1";
  m.sequence = sequence;
  m.grid = core::OccupancyGrid(core::GridGeometry(0.05, 130, 70));  // 3 x 2 tiles
  m.grid.SetState({5, 5}, core::CellState::kOccupied);
  m.start_s = 1, m.end_s = 2;
  return m;
}

TEST(TempMapOutboxTest, SendsResendsWithBackoffAndStopsWhenMerged) {
  OutboxOptions options;
  options.first_resend_s = 1.0;
  options.max_resend_s = 4.0;
  TempMapOutbox outbox(options);
  ASSERT_TRUE(outbox.Add(Map(1), 0.0).ok());
  EXPECT_EQ(outbox.Due(0.0).size(), 6u);
  EXPECT_TRUE(outbox.Due(0.5).empty());  // waiting for the acknowledgement
  outbox.OnAck(1, {0, 1, 2, 3}, AckOutcome::kPending);
  EXPECT_EQ(outbox.Due(1.0).size(), 2u);  // only what was not confirmed
  EXPECT_TRUE(outbox.Due(1.9).empty());
  EXPECT_EQ(outbox.Due(2.0).size(), 2u);  // no answer since: the backoff doubles
  EXPECT_TRUE(outbox.Due(3.9).empty());
  EXPECT_EQ(outbox.Due(4.0).size(), 2u);
  EXPECT_TRUE(outbox.Due(7.9).empty());  // capped at 4 s: next at 8.0
  EXPECT_EQ(outbox.Due(8.0).size(), 2u);
  outbox.OnAck(1, {}, AckOutcome::kMerged);
  EXPECT_EQ(outbox.pending(), 0u);
  EXPECT_TRUE(outbox.Due(100.0).empty());
  EXPECT_EQ(outbox.counters().tiles_sent, 6);
  EXPECT_EQ(outbox.counters().tiles_resent, 8);
}

TEST(TempMapOutboxTest, KeepsResendingEverySecondWhileTilesGetThrough) {
  OutboxOptions options;
  options.first_resend_s = 1.0;
  options.max_resend_s = 16.0;
  TempMapOutbox outbox(options);
  ASSERT_TRUE(outbox.Add(Map(1), 0.0).ok());
  ASSERT_EQ(outbox.Due(0.0).size(), 6u);
  EXPECT_TRUE(outbox.Due(0.9).empty());
  ASSERT_EQ(outbox.Due(1.0).size(), 6u);             // nothing heard: backoff 2 s from here
  outbox.OnAck(1, {0, 1, 2}, AckOutcome::kPending);  // a lossy link, not an absent aggregator
  EXPECT_TRUE(outbox.Due(1.9).empty());
  ASSERT_EQ(outbox.Due(2.0).size(), 3u);  // 1 s after the last send, not 2
  outbox.OnAck(1, {0, 1, 2, 3}, AckOutcome::kPending);
  ASSERT_EQ(outbox.Due(3.0).size(), 2u);
  // An acknowledgement that confirms nothing new is no progress: the backoff goes on.
  outbox.OnAck(1, {0, 1, 2, 3}, AckOutcome::kPending);
  EXPECT_TRUE(outbox.Due(3.9).empty());
  EXPECT_EQ(outbox.Due(4.0).size(), 2u);
  EXPECT_TRUE(outbox.Due(5.9).empty());
  EXPECT_EQ(outbox.Due(6.0).size(), 2u);
  EXPECT_TRUE(outbox.Due(9.9).empty());
  EXPECT_EQ(outbox.Due(10.0).size(), 2u);
}

TEST(TempMapOutboxTest, SurvivesARestartThroughItsStateFolder) {
  OutboxOptions options;
  options.state_dir = ::testing::TempDir() + "/outbox_test";
  std::filesystem::remove_all(options.state_dir);
  {
    TempMapOutbox outbox(options);
    ASSERT_TRUE(outbox.Add(Map(1), 0.0).ok());
    ASSERT_TRUE(outbox.Add(Map(2), 0.0).ok());
    outbox.OnAck(1, {}, AckOutcome::kRejected);  // finished with: gone from disk too
  }
  std::ofstream(options.state_dir + "/tempmap_9.fmtm") << "garbage";
  TempMapOutbox restarted(options);
  EXPECT_EQ(restarted.LoadPersisted(10.0), 1);
  EXPECT_EQ(restarted.counters().persist_errors, 1);
  EXPECT_TRUE(std::filesystem::exists(options.state_dir + "/tempmap_9.fmtm.corrupt"));
  const auto due = restarted.Due(10.0);
  ASSERT_EQ(due.size(), 6u);
  EXPECT_EQ(due[0].sequence, 2);
  std::filesystem::remove_all(options.state_dir);
}

TEST(TempMapOutboxTest, BoundedByDroppingTheOldest) {
  OutboxOptions options;
  options.max_pending_maps = 2;
  TempMapOutbox outbox(options);
  for (int s = 1; s <= 3; ++s) ASSERT_TRUE(outbox.Add(Map(s), 0.0).ok());
  EXPECT_EQ(outbox.pending(), 2u);
  EXPECT_EQ(outbox.counters().maps_dropped, 1);
  EXPECT_EQ(outbox.Due(0.0).front().sequence, 2);
}

// Maps merged into versions 5, 6, 7 are retained; the aggregator recovers at version 5 and
// asks: the two after it are sent again, whole, and once merged again retained again.
void ExpectRetainsAndResendsAfterARecovery(const OutboxOptions& options) {
  TempMapOutbox outbox(options);
  for (int s = 1; s <= 3; ++s) {
    ASSERT_TRUE(outbox.Add(Map(s), 0.0).ok());
    ASSERT_EQ(outbox.Due(0.0).size(), 6u);
    outbox.OnAck(s, {}, AckOutcome::kMerged, 4 + s);
  }
  ASSERT_TRUE(outbox.Add(Map(4), 0.0).ok());
  outbox.OnAck(4, {}, AckOutcome::kRejected, 7);  // not merged: nothing to keep
  EXPECT_EQ(outbox.pending(), 0u);
  EXPECT_EQ(outbox.retained().size(), 3u);
  EXPECT_GT(outbox.retained().bytes(), 0);

  EXPECT_EQ(outbox.ResendMergedAfter(5, 10.0), 2);
  EXPECT_EQ(outbox.pending(), 2u);
  EXPECT_EQ(outbox.retained().size(), 1u);
  const auto due = outbox.Due(10.0);
  ASSERT_EQ(due.size(), 12u);
  EXPECT_EQ(due.front().sequence, 2);
  EXPECT_EQ(due.back().sequence, 3);
  outbox.OnAck(2, {}, AckOutcome::kMerged, 6);
  outbox.OnAck(3, {}, AckOutcome::kDuplicate, 7);
  EXPECT_EQ(outbox.retained().size(), 3u);
  EXPECT_EQ(outbox.ResendMergedAfter(7, 20.0), 0);
  EXPECT_EQ(outbox.counters().maps_resent_after_recovery, 2);
}

TEST(TempMapOutboxTest, MergedMapsAreKeptAndSentAgainAfterARecovery) {
  ExpectRetainsAndResendsAfterARecovery({});
  OutboxOptions on_disk;
  on_disk.state_dir = ::testing::TempDir() + "/outbox_retain_test";
  std::filesystem::remove_all(on_disk.state_dir);
  ExpectRetainsAndResendsAfterARecovery(on_disk);
  std::filesystem::remove_all(on_disk.state_dir);
}

// On disk, the kept maps survive a restart, and a map sent again is pending on disk too.
TEST(TempMapOutboxTest, KeptMapsSurviveARestart) {
  OutboxOptions options;
  options.state_dir = ::testing::TempDir() + "/outbox_retain_restart_test";
  std::filesystem::remove_all(options.state_dir);
  {
    TempMapOutbox outbox(options);
    for (int s = 1; s <= 2; ++s) {
      ASSERT_TRUE(outbox.Add(Map(s), 0.0).ok());
      outbox.OnAck(s, {}, AckOutcome::kMerged, s);
    }
    EXPECT_FALSE(std::filesystem::exists(options.state_dir + "/tempmap_1.fmtm"));
  }
  {
    TempMapOutbox restarted(options);
    EXPECT_EQ(restarted.LoadPersisted(5.0), 0);  // nothing pending
    EXPECT_EQ(restarted.retained().size(), 2u);
    EXPECT_EQ(restarted.ResendMergedAfter(1, 5.0), 1);
    EXPECT_TRUE(std::filesystem::exists(options.state_dir + "/tempmap_2.fmtm"));
  }
  TempMapOutbox again(options);
  EXPECT_EQ(again.LoadPersisted(6.0), 1);  // the map sent again is still pending
  EXPECT_EQ(again.retained().size(), 1u);
  std::filesystem::remove_all(options.state_dir);
}

// Kept for retain_merged_s after a map's end (the clock of the newest map) and up to
// max_retained_bytes, the oldest dropped first; 0 bytes keeps none.
TEST(TempMapOutboxTest, KeptMapsAreBoundedInTimeAndBytes) {
  OutboxOptions options;
  options.retain_merged_s = 100.0;
  TempMapOutbox outbox(options);
  for (int s = 1; s <= 3; ++s) {
    ASSERT_TRUE(outbox.Add(Map(s), 0.0).ok());
    outbox.OnAck(s, {}, AckOutcome::kMerged, s);
  }
  const int64_t three = outbox.retained().bytes();
  core::TempMap later = Map(4);
  later.start_s = 101.5, later.end_s = 102.5;  // maps that ended at 2 s are over 100 s old
  ASSERT_TRUE(outbox.Add(later, 0.0).ok());
  EXPECT_EQ(outbox.retained().size(), 0u);

  options.retain_merged_s = 86400.0;
  options.max_retained_bytes = three * 2 / 3;
  TempMapOutbox small(options);
  for (int s = 1; s <= 3; ++s) {
    ASSERT_TRUE(small.Add(Map(s), 0.0).ok());
    small.OnAck(s, {}, AckOutcome::kMerged, s);
  }
  EXPECT_EQ(small.retained().size(), 2u);
  EXPECT_EQ(small.ResendMergedAfter(0, 1.0), 2);
  EXPECT_EQ(small.Due(1.0).front().sequence, 2);  // the oldest went first

  options.max_retained_bytes = 0;
  TempMapOutbox none(options);
  ASSERT_TRUE(none.Add(Map(1), 0.0).ok());
  none.OnAck(1, {}, AckOutcome::kMerged, 1);
  EXPECT_EQ(none.retained().size(), 0u);
}

TEST(TempMapOutboxTest, RefusesAnInvalidMap) {
  TempMapOutbox outbox({});
  core::TempMap bad = Map(1);
  bad.vehicle_id.clear();
  EXPECT_FALSE(outbox.Add(bad, 0.0).ok());
  EXPECT_EQ(outbox.pending(), 0u);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
