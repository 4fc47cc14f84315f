// The node's small parts: the input queue, the stored temporary-map numbering, vehicle ids.
#include <gtest/gtest.h>

#include <fstream>

#include "core/map/temp_map_file.h"
#include "tests/support/scratch_folder.h"
#include "vehicle_agent/node/agent_node_options.h"
#include "vehicle_agent/node/input_queue.h"
#include "vehicle_agent/node/sequence_store.h"
#include "vehicle_agent/node/tile_send_queue.h"

namespace fleetmap::vehicle_agent::node {
namespace {

core::LaserScan ScanAt(double t) {
  core::LaserScan s;
  s.stamp_s = t;
  return s;
}

TEST(InputQueueTest, KeepsOrderAndSkipsAllButTheNewestScanWhenBehind) {
  InputQueue q({3, 4096});
  q.Push(ScanAt(1));
  q.Push(core::OdometrySample{1.5, {}, 0, 0});
  q.Push(ScanAt(2));
  auto taken = q.TakeAll();  // two scans: not behind
  ASSERT_EQ(taken.size(), 3u);
  EXPECT_EQ(std::get<core::LaserScan>(taken[2]).stamp_s, 2.0);
  for (int i = 0; i < 5; ++i) {
    q.Push(ScanAt(10 + i));
    q.Push(core::OdometrySample{10.5 + i, {}, 0, 0});
  }
  taken = q.TakeAll();
  ASSERT_EQ(taken.size(), 6u);  // five odometry samples and the newest scan
  EXPECT_EQ(std::get<core::LaserScan>(taken[4]).stamp_s, 14.0);
  EXPECT_EQ(q.scans_skipped(), 4);
  EXPECT_EQ(q.size(), 0u);
}

TEST(InputQueueTest, AHardBoundDropsTheOldestAndCountsIt) {
  InputQueue q({3, 16});
  for (int i = 0; i < 20; ++i) q.Push(core::OdometrySample{double(i), {}, 0, 0});
  EXPECT_EQ(q.size(), 16u);
  EXPECT_EQ(q.inputs_dropped(), 4);
}

TEST(SequenceStoreTest, NumberingGoesOnAcrossRestartsAndNeverReusesAPendingMap) {
  fleetmap::testing::ScratchFolder dir;
  EXPECT_EQ(SequenceStore("").Load().next, 1);
  SequenceStore store(dir.File("state"));
  StoredSequence s = store.Load();
  EXPECT_EQ(s.next, 1);
  EXPECT_TRUE(s.issue.ok());  // a first start
  ASSERT_TRUE(store.Store(8).ok());
  EXPECT_EQ(store.Load().next, 8);
  // A pending map numbered above the counter wins (the counter file was older).
  std::ofstream(dir.File("state/tempmap_12.fmtm")) << "x";
  std::ofstream(dir.File("state/tempmap_x.fmtm")) << "x";
  EXPECT_EQ(store.Load().next, 13);
  // A corrupt counter is reported, and the pending files still keep numbers apart.
  std::ofstream(store.path()) << "seven\n";
  s = store.Load();
  EXPECT_FALSE(s.issue.ok());
  EXPECT_EQ(s.next, 13);
  std::ofstream(store.path()) << "-4\n";
  EXPECT_FALSE(store.Load().issue.ok());
}

TEST(AgentNodeOptionsTest, VehicleIdsMustBeSafeInChannelNames) {
  EXPECT_TRUE(CheckVehicleId("cts_1-A").ok());
  for (const char* bad : {"", "v 1", "v.1", "v*", "TEMPMAP_.*"})
    EXPECT_FALSE(CheckVehicleId(bad).ok()) << bad;
  EXPECT_FALSE(CheckVehicleId(std::string(65, 'a')).ok());
  AgentNodeOptions o;
  o.pipeline.vehicle_id = "v1";
  EXPECT_TRUE(o.Validate().ok());
  o.initial_pose = InitialPoseSource::kFirstExternal;
  EXPECT_FALSE(o.Validate().ok());  // needs external poses
  o.use_external_pose = true;
  EXPECT_TRUE(o.Validate().ok());
  o.status_period_s = 0;
  EXPECT_FALSE(o.Validate().ok());
}

TEST(TileSendQueueTest, PacesBurstsQueuesEachTileOnceAndDropsAcknowledgedOnes) {
  TileSendQueue q(core::PacerOptions{100.0, 4.0});
  std::vector<core::TempMapTile> tiles(10);
  for (int i = 0; i < 10; ++i) tiles[i].sequence = 7, tiles[i].index = i;
  q.Add(tiles);
  q.Add(tiles);  // due again before the first copies left
  EXPECT_EQ(q.size(), 10u);
  EXPECT_EQ(q.Take(1.0).size(), 4u);                        // the burst
  EXPECT_EQ(q.Take(1.0).size(), 0u);                        // nothing more at once
  EXPECT_EQ(q.Take(1.02).size(), 2u);                       // 100 per second
  q.Drop(7, [](int32_t index) { return index % 2 == 0; });  // received: 6 and 8
  const auto rest = q.Take(5.0, /*all=*/true);
  ASSERT_EQ(rest.size(), 2u);
  EXPECT_EQ(rest[0].index, 7);
  EXPECT_EQ(rest[1].index, 9);
  q.Add(tiles);  // the queue is empty: a resend queues every tile again
  EXPECT_EQ(q.size(), 10u);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
