// The node's small parts: configuration file, tile spool, map hash, request coalescing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "aggregator/node/keyframe_schedule.h"
#include "aggregator/node/map_hash.h"
#include "aggregator/node/node_config.h"
#include "aggregator/node/tile_spool.h"
#include "tests/aggregator/test_files.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator::node {
namespace {

TEST(AggregatorNodeConfigTest, EmptyFileGivesTheDefaults) {
  auto c = ParseProcessConfig("{}", "agg.yaml");
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_EQ(c->uplink_url, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(c->downlink_url, "udpm://239.255.76.68:7668?ttl=0");
  EXPECT_TRUE(c->state_dir.empty());
  EXPECT_EQ(c->node.pending_ack_interval_s, 0.5);
  EXPECT_EQ(c->node.keyframe_period_s, 10.0);
  EXPECT_EQ(c->aggregator.merge.confirmations, 2);
}

// The packaged configuration says it holds every key with its default: it must, or a site
// that edits one key inherits stale values for the others.
TEST(AggregatorNodeConfigTest, ThePackagedFileHoldsTheDefaults) {
  auto c = LoadProcessConfig(std::string(FLEETMAP_SOURCE_DIR) + "/packaging/etc/aggregator.yaml");
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  const AggregatorProcessConfig d = DefaultProcessConfig();
  const AggregatorNodeOptions &n = c->node, &nd = d.node;
  EXPECT_EQ(n.pending_ack_interval_s, nd.pending_ack_interval_s);
  EXPECT_EQ(n.keyframe_period_s, nd.keyframe_period_s);
  EXPECT_EQ(n.downlink_bytes_per_s, nd.downlink_bytes_per_s);
  EXPECT_EQ(n.downlink_messages_per_s, nd.downlink_messages_per_s);
  EXPECT_EQ(n.keyframe_share, nd.keyframe_share);
  EXPECT_EQ(n.status_period_s, nd.status_period_s);
  EXPECT_EQ(n.pending_map_timeout_s, nd.pending_map_timeout_s);
  EXPECT_EQ(n.max_message_bytes, nd.max_message_bytes);
  EXPECT_EQ(n.max_report_matches, nd.max_report_matches);
  EXPECT_EQ(n.max_remembered_rejections, nd.max_remembered_rejections);
  EXPECT_EQ(n.max_retry_maps, nd.max_retry_maps);
  EXPECT_EQ(n.assembler.tile_size_cells, nd.assembler.tile_size_cells);
  EXPECT_EQ(n.assembler.max_pending_maps, nd.assembler.max_pending_maps);
  EXPECT_EQ(n.assembler.max_map_cells, nd.assembler.max_map_cells);
  EXPECT_EQ(n.assembler.max_tiles, nd.assembler.max_tiles);
  const MergeOptions &m = c->aggregator.merge, &md = d.aggregator.merge;
  EXPECT_EQ(m.add_min_log_odds, md.add_min_log_odds);
  EXPECT_EQ(m.remove_max_log_odds, md.remove_max_log_odds);
  EXPECT_EQ(m.static_clearance_m, md.static_clearance_m);
  EXPECT_EQ(m.wall_offset_window_m, md.wall_offset_window_m);
  EXPECT_EQ(m.held_wall_clearance_m, md.held_wall_clearance_m);
  EXPECT_EQ(m.min_occupied_neighbours, md.min_occupied_neighbours);
  EXPECT_EQ(m.removal_clearance_m, md.removal_clearance_m);
  EXPECT_EQ(m.confirmations, md.confirmations);
  EXPECT_EQ(m.confirm_radius_m, md.confirm_radius_m);
  EXPECT_EQ(m.confirm_min_gap_s, md.confirm_min_gap_s);
  EXPECT_EQ(m.confirm_max_gap_s, md.confirm_max_gap_s);
  EXPECT_EQ(m.confirm_by_watch, md.confirm_by_watch);
  EXPECT_EQ(m.watch_join_s, md.watch_join_s);
  const CellAlignmentOptions &a = c->aggregator.cell_alignment, &ad = d.aggregator.cell_alignment;
  EXPECT_EQ(a.use, ad.use);
  EXPECT_EQ(a.range_m, ad.range_m);
  EXPECT_NEAR(a.range_rad, ad.range_rad, 1e-12);
  EXPECT_EQ(a.lines_min_relative_score, ad.lines_min_relative_score);
  EXPECT_EQ(c->aggregator.store.retained_deltas, d.aggregator.store.retained_deltas);
  EXPECT_EQ(c->aggregator.store.tiles.tile_size_cells, d.aggregator.store.tiles.tile_size_cells);
  EXPECT_EQ(c->aggregator.persistence.snapshot_every_merges,
            d.aggregator.persistence.snapshot_every_merges);
}

TEST(AggregatorNodeConfigTest, KeysAreReadIntoTheirStructs) {
  auto c = ParseProcessConfig(R"(
uplink_url: "udpm://239.255.1.1:7000?ttl=1"
state_dir: state
node: {keyframe_period_s: 0, status_period_s: 2.5, max_report_matches: 8}
assembler: {max_pending_maps: 4, max_tiles: 100}
aggregator:
  merge: {confirmations: 1, confirm_min_gap_s: 5, confirm_max_gap_s: 40, static_clearance_m: 0.08,
          confirm_by_watch: true, watch_join_s: 0.5, wall_offset_window_m: 0.2,
          held_wall_clearance_m: 0.15}
  cell_alignment: {use: where_lines_fail, range_m: 0.5, range_deg: 4,
                   lines_min_relative_score: 0.5}
  store: {retained_deltas: 3}
  persistence: {snapshot_every_merges: 7}
)",
                              "/etc/fleetmap/agg.yaml");
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_EQ(c->uplink_url, "udpm://239.255.1.1:7000?ttl=1");
  EXPECT_EQ(c->state_dir, "/etc/fleetmap/state");  // relative to the file
  EXPECT_EQ(c->node.keyframe_period_s, 0.0);
  EXPECT_EQ(c->node.status_period_s, 2.5);
  EXPECT_EQ(c->node.max_report_matches, 8);
  EXPECT_EQ(c->node.assembler.max_pending_maps, 4);
  EXPECT_EQ(c->node.assembler.max_tiles, 100);
  EXPECT_EQ(c->aggregator.merge.confirmations, 1);
  EXPECT_EQ(c->aggregator.merge.confirm_min_gap_s, 5.0);
  EXPECT_EQ(c->aggregator.merge.confirm_max_gap_s, 40.0);
  EXPECT_EQ(c->aggregator.merge.static_clearance_m, 0.08);
  EXPECT_EQ(c->aggregator.merge.wall_offset_window_m, 0.2);
  EXPECT_EQ(c->aggregator.merge.held_wall_clearance_m, 0.15);
  EXPECT_TRUE(c->aggregator.merge.confirm_by_watch);
  EXPECT_EQ(c->aggregator.merge.watch_join_s, 0.5);
  EXPECT_EQ(c->aggregator.cell_alignment.use, CellAlignmentUse::kWhereLinesFail);
  EXPECT_EQ(c->aggregator.cell_alignment.range_m, 0.5);
  EXPECT_NEAR(c->aggregator.cell_alignment.range_rad, 4 * M_PI / 180, 1e-12);
  EXPECT_EQ(c->aggregator.cell_alignment.lines_min_relative_score, 0.5);
  EXPECT_EQ(c->aggregator.store.retained_deltas, 3);
  EXPECT_EQ(c->aggregator.persistence.snapshot_every_merges, 7);
}

TEST(AggregatorNodeConfigTest, MistakesNameTheFieldAndTheLine) {
  auto typo = ParseProcessConfig("node:\n  keyframe_period: 3\n", "agg.yaml");
  ASSERT_FALSE(typo.ok());
  EXPECT_NE(typo.status().message().find("agg.yaml:2: node.keyframe_period: unknown key"),
            std::string::npos)
      << typo.status().ToString();
  auto bad = ParseProcessConfig("node: {status_period_s: -1}", "agg.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("node.status_period_s"), std::string::npos);
  auto type = ParseProcessConfig("assembler: {max_tiles: lots}", "agg.yaml");
  ASSERT_FALSE(type.ok());
  EXPECT_NE(type.status().message().find("assembler.max_tiles"), std::string::npos);
  // A key of an earlier version, in cells, names the key in metres that replaced it.
  auto cells =
      ParseProcessConfig("aggregator:\n  merge: {static_clearance_cells: 2}\n", "agg.yaml");
  ASSERT_FALSE(cells.ok());
  EXPECT_NE(cells.status().message().find("is now static_clearance_m, in metres"),
            std::string::npos)
      << cells.status().ToString();
  auto nested = ParseProcessConfig("aggregator: {merge: {confirmation: 1}}", "agg.yaml");
  ASSERT_FALSE(nested.ok());
  EXPECT_NE(nested.status().message().find("aggregator.merge.confirmation: unknown key"),
            std::string::npos);
  auto use = ParseProcessConfig("aggregator: {cell_alignment: {use: always}}", "agg.yaml");
  ASSERT_FALSE(use.ok());
  EXPECT_NE(use.status().message().find("aggregator.cell_alignment.use"), std::string::npos);
  EXPECT_NE(use.status().message().find("known: off, where_lines_fail, first"), std::string::npos);
  EXPECT_FALSE(ParseProcessConfig("assembler: {max_tiles: 40000}", "agg.yaml").ok());
  EXPECT_FALSE(ParseProcessConfig("[1, 2]", "agg.yaml").ok());
  EXPECT_FALSE(LoadProcessConfig("/nonexistent/agg.yaml").ok());
}

TEST(AggregatorNodeTileSpoolTest, KeptTilesComeBackAndGoWithTheirMap) {
  fleetmap::testing::ScratchFolder folder;
  const std::string dir = folder.File("incoming");
  const MapKey a{"v 1/../x", 3}, b{"v2", -4};  // ids are hex-encoded into file names
  {
    auto spool = TileSpool::Open(dir);
    ASSERT_TRUE(spool.ok()) << spool.status().ToString();
    ASSERT_TRUE(spool->Save(a, 0, {1, 2, 3}).ok());
    ASSERT_TRUE(spool->Save(a, 7, {4}).ok());
    ASSERT_TRUE(spool->Save(b, 1, {5, 6}).ok());
    EXPECT_TRUE(spool->Has(a, 7));
    EXPECT_FALSE(spool->Has(a, 1));
  }
  std::ofstream(dir + "/notes.txt") << "not ours";
  auto spool = TileSpool::Open(dir);
  int bad = 0;
  const auto tiles = spool->LoadAll(&bad);
  EXPECT_EQ(bad, 0);
  ASSERT_EQ(tiles.size(), 3u);
  EXPECT_EQ(tiles[0].key, a);
  EXPECT_EQ(tiles[0].index, 0);
  EXPECT_EQ(tiles[0].bytes, (std::vector<uint8_t>{1, 2, 3}));
  EXPECT_EQ(tiles[1].index, 7);
  EXPECT_EQ(tiles[2].key, b);
  spool->Remove(a);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.path() != "";
  EXPECT_EQ(files, 2);  // b's tile and the foreign file
  EXPECT_FALSE(TileSpool().enabled());
  EXPECT_FALSE(TileSpool().Save(a, 0, {1}).ok());
}

TEST(AggregatorNodeTileSpoolTest, AnUnusableFolderIsAnError) {
  fleetmap::testing::ScratchFolder folder;
  std::ofstream(folder.File("file")) << "x";
  EXPECT_FALSE(TileSpool::Open(folder.File("file")).ok());
}

TEST(AggregatorNodeMapHashTest, EqualMapsEqualHashesAnyCellOrGeometryChangesIt) {
  const core::OccupancyGrid hall = aggregator::testing::HallMap();
  const uint64_t h = MapHash(hall);
  EXPECT_EQ(MapHash(aggregator::testing::HallMap()), h);
  core::OccupancyGrid cell = hall;
  cell.SetState({200, 200}, core::CellState::kOccupied);
  EXPECT_NE(MapHash(cell), h);
  core::OccupancyGrid moved(core::GridGeometry(0.05, 400, 400, core::Pose2(0.05, 0, 0)));
  moved.mutable_cells() = hall.cells();
  EXPECT_NE(MapHash(moved), h);
  EXPECT_EQ(HashHex(0x1234), "0000000000001234");
  EXPECT_EQ(FinalLine(3, 0xabc, 2, 1),
            "aggregator: version 3 map_hash 0000000000000abc merged 2 rejected 1");
}

// Asked tiles wait once however often they are asked for, and go without waiting for a pace;
// the rolling keyframe sends every tile in turn at one round per period.
TEST(KeyframeScheduleTest, AskedTilesOnceAndFirstThenEveryTileInTurnAtThePace) {
  KeyframeSchedule s(10, /*period_s=*/5.0, /*now_s=*/100.0);  // 2 tiles/s
  EXPECT_FALSE(s.NextAsked());
  EXPECT_FALSE(s.NextRolling(100.0));
  s.Ask({4, 2});
  s.Ask({2, 9, 12, -1});  // 2 again; 12 and -1 are no tiles of the map
  EXPECT_EQ(s.asked(), 3);
  std::vector<int32_t> sent;
  while (auto t = s.NextAsked()) sent.push_back(*t);
  EXPECT_EQ(sent, (std::vector<int32_t>{2, 4, 9}));
  EXPECT_EQ(s.asked_sent(), 3);
  EXPECT_FALSE(s.NextRolling(100.4));
  EXPECT_EQ(s.NextRolling(100.5), 0) << "the rolling keyframe: one tile per 0.5 s";
  EXPECT_FALSE(s.NextRolling(100.9));
  EXPECT_EQ(s.NextRolling(101.0), 1);
  s.Ask({});  // every tile
  EXPECT_EQ(s.asked(), 10);
  sent.clear();
  while (auto t = s.NextAsked()) sent.push_back(*t);
  EXPECT_EQ(sent.size(), 10u) << "asked tiles go without waiting for the pace";
  sent.clear();
  for (double t = 101.5; t <= 105.01; t += 0.5) sent.push_back(*s.NextRolling(t));
  EXPECT_EQ(sent, (std::vector<int32_t>{2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(s.rounds(), 1);
  EXPECT_EQ(s.NextRolling(200.0), 0);
  EXPECT_EQ(s.NextRolling(200.0), 1) << "at most a second of the pace after a pause";
  EXPECT_FALSE(s.NextRolling(200.0));
}

TEST(KeyframeScheduleTest, APeriodOfZeroSendsOnlyWhatIsAsked) {
  KeyframeSchedule s(4, 0.0, 0.0);
  EXPECT_FALSE(s.NextRolling(1e6));
  s.Ask({3});
  EXPECT_EQ(s.NextAsked(), 3);
  EXPECT_FALSE(s.NextAsked());
  EXPECT_FALSE(s.NextRolling(2e6));
}

}  // namespace
}  // namespace fleetmap::aggregator::node
