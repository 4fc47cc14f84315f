// Temporary maps from closing to acknowledgement: numbering on disk, pacing, acknowledgements
// and the resend after an aggregator's recovery.
#include "vehicle_agent/node/tempmap_uplink.h"

#include <gtest/gtest.h>

#include "lcmtypes/channels.h"
#include "tests/support/scratch_folder.h"

namespace fleetmap::vehicle_agent::node {
namespace {

core::TempMap Map(int32_t sequence) {
  core::TempMap m;
  m.vehicle_id = "v1";
  m.sequence = sequence;
  m.grid = core::OccupancyGrid(core::GridGeometry(0.05, 130, 70));  // 3 x 2 tiles of 64 cells
  m.grid.SetState({5, 5}, core::CellState::kOccupied);
  m.start_s = 1, m.end_s = 2;
  return m;
}

fleetmap::tempmap_ack_t Ack(int32_t sequence, int8_t outcome, std::vector<int16_t> received,
                            int32_t map_version = -1) {
  fleetmap::tempmap_ack_t a;
  a.vehicle_id = "v1";
  a.tempmap_seq = sequence;
  a.tile_count = 6;
  a.num_received = static_cast<int32_t>(received.size());
  a.received_tiles = std::move(received);
  a.outcome = outcome;
  a.map_version = map_version;
  return a;
}

class TempMapUplinkTest : public ::testing::Test {
 protected:
  TempMapUplinkTest() : log_([this](LogLevel, const std::string& l) { lines_.push_back(l); }) {}

  std::unique_ptr<TempMapUplink> Make(const std::string& state_dir) {
    OutboxOptions outbox;
    outbox.state_dir = state_dir;
    return std::make_unique<TempMapUplink>(outbox, core::PacerOptions{100.0, 2.0}, &log_,
                                           &counters_);
  }
  bool Logged(const std::string& text) const {
    for (const std::string& l : lines_)
      if (l.find(text) != std::string::npos) return true;
    return false;
  }

  std::vector<std::string> lines_;
  CauseLog log_;
  AgentNodeCounters counters_;
};

TEST_F(TempMapUplinkTest, NumbersGoOnDiskABlockAheadBeforeAMapLeavesAndPendingMapsReload) {
  fleetmap::testing::ScratchFolder dir;
  auto uplink = Make(dir.path());
  uplink->StartNumberingAt(5);
  const int32_t block = TempMapUplink::kSequenceBlock;
  EXPECT_EQ(uplink->reserved(), 5 + block);
  EXPECT_EQ(SequenceStore(dir.path()).Load().next, 5 + block);
  uplink->Keep(Map(5 + block - 1), 0.0);  // inside the block: nothing to store
  EXPECT_EQ(uplink->reserved(), 5 + block);
  uplink->Keep(Map(5 + block), 0.0);  // the first number past it reserves the next block
  EXPECT_EQ(uplink->reserved(), 5 + 2 * block);
  EXPECT_EQ(SequenceStore(dir.path()).Load().next, 5 + 2 * block);
  EXPECT_EQ(counters_.tempmaps_closed, 2);
  EXPECT_EQ(uplink->outbox().pending(), 2u);
  EXPECT_TRUE(Logged("temporary map 37 closed: 130 x 70 cells over 1 s"));

  // A restart over the same folder sends both again.
  auto again = Make(dir.path());
  EXPECT_EQ(again->ReloadPending(10.0), 2);
  EXPECT_TRUE(Logged("2 unacknowledged temporary map(s) reloaded from " + dir.path()));
  EXPECT_EQ(again->TakeDue(10.0, /*all=*/true).size(), 12u);
}

TEST_F(TempMapUplinkTest, TilesLeaveAtThePacersRateAndAcknowledgedOnesLeaveTheQueueUnsent) {
  auto uplink = Make("");
  uplink->Keep(Map(1), 0.0);
  std::vector<core::TempMapTile> sent = uplink->TakeDue(0.0);
  ASSERT_EQ(sent.size(), 2u);  // the burst
  EXPECT_EQ(sent[0].index, 0);
  EXPECT_EQ(sent[1].index, 1);
  EXPECT_EQ(uplink->tiles_queued(), 4u);

  ASSERT_TRUE(uplink->OnAck(Ack(1, fleetmap::tempmap_ack_t::PENDING, {0, 1, 2})).ok());
  EXPECT_EQ(counters_.acks, 1);
  EXPECT_EQ(uplink->tiles_queued(), 3u);  // tile 2 got there before it left
  EXPECT_EQ(uplink->outbox().pending(), 1u);
  sent = uplink->TakeDue(0.01);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].index, 3);

  ASSERT_TRUE(uplink->OnAck(Ack(1, fleetmap::tempmap_ack_t::MERGED, {}, 4)).ok());
  EXPECT_EQ(counters_.maps_merged, 1);
  EXPECT_EQ(uplink->outbox().pending(), 0u);
  EXPECT_EQ(uplink->tiles_queued(), 0u);  // a merged map's tiles are needless
  EXPECT_TRUE(Logged("temporary map 1 merged: map version 4"));
  // The same final acknowledgement again changes nothing but the count of acknowledgements.
  ASSERT_TRUE(uplink->OnAck(Ack(1, fleetmap::tempmap_ack_t::MERGED, {}, 4)).ok());
  EXPECT_EQ(counters_.acks, 3);
  EXPECT_EQ(counters_.maps_merged, 1);
}

TEST_F(TempMapUplinkTest, RefusesAcknowledgementsThatCannotBe) {
  auto uplink = Make("");
  uplink->Keep(Map(1), 0.0);
  const core::Status unknown = uplink->OnAck(Ack(1, 9, {}));
  EXPECT_EQ(unknown.code(), core::StatusCode::kInvalidArgument);
  const core::Status outside = uplink->OnAck(Ack(1, fleetmap::tempmap_ack_t::MERGED, {0, 6}, 4));
  EXPECT_EQ(outside.code(), core::StatusCode::kOutOfRange);
  EXPECT_EQ(counters_.acks, 0);
  EXPECT_EQ(counters_.maps_merged, 0);
  EXPECT_EQ(uplink->outbox().pending(), 1u);
}

TEST_F(TempMapUplinkTest, ARecoveryIsAnsweredOnceWithTheMapsMergedAfterItsVersion) {
  auto uplink = Make("");
  uplink->Keep(Map(1), 0.0);
  uplink->Keep(Map(2), 0.0);
  ASSERT_EQ(uplink->TakeDue(0.0, /*all=*/true).size(), 12u);
  ASSERT_TRUE(uplink->OnAck(Ack(1, fleetmap::tempmap_ack_t::MERGED, {}, 3)).ok());
  ASSERT_TRUE(uplink->OnAck(Ack(2, fleetmap::tempmap_ack_t::MERGED, {}, 5)).ok());
  ASSERT_EQ(uplink->outbox().pending(), 0u);

  fleetmap::status_t status;
  status.counter_names = {lcmtypes::kRecoveryIdCounter, lcmtypes::kRecoveredVersionCounter};
  status.counter_values = {7, 4};
  status.num_counters = 2;
  uplink->OnAggregatorStatus(status, 1.0);
  EXPECT_EQ(uplink->outbox().pending(), 1u);  // map 2 (version 5), not map 1 (version 3)
  EXPECT_EQ(uplink->outbox().counters().maps_resent_after_recovery, 1);
  EXPECT_TRUE(Logged("recovered its map at version 4: 1 merged temporary map(s)"));
  const std::vector<core::TempMapTile> resent = uplink->TakeDue(1.0, /*all=*/true);
  ASSERT_EQ(resent.size(), 6u);
  EXPECT_EQ(resent[0].sequence, 2);

  // The heartbeat repeats the recovery: it is answered once.
  ASSERT_TRUE(uplink->OnAck(Ack(2, fleetmap::tempmap_ack_t::MERGED, {}, 5)).ok());
  uplink->OnAggregatorStatus(status, 2.0);
  EXPECT_EQ(uplink->outbox().pending(), 0u);
  EXPECT_EQ(uplink->outbox().counters().maps_resent_after_recovery, 1);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
