// A recorded run read back: merges, versions, traces and the change latency rebuilt from the
// logs, a change some vehicle never holds, a delta that does not fit the map, the agents' CPU
// and memory from their STATUS, and logs that are missing or empty.
#include "eval/recording/recorded_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>

#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"
#include "sim/scenario.h"
#include "tests/eval/recording/recorded_run_fixture.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::eval::recording {
namespace {

using testing::kEpoch;
using testing::kScenario;
using testing::RecordedRunTest;

TEST_F(RecordedRunTest, RebuildsMergesVersionsTracesAndLatency) {
  {
    lcm::LogFile log(path_, "w");
    ASSERT_TRUE(log.good());
    WriteMergeRun(log);
  }
  const core::Pose2 anchor = MergeRunAnchor();
  const core::TempMap map = MergeRunMap();
  RecordedRunOptions options;
  options.epoch_s = kEpoch;
  auto run = ReadRecordedRun({path_}, *world_, options);
  ASSERT_TRUE(run.ok()) << run.status().ToString();

  ASSERT_EQ(run->run.merges.size(), 1u);
  const eval::MergeRecord& m = run->run.merges[0];
  EXPECT_TRUE(m.accepted);
  EXPECT_EQ(m.tempmap_seq, 3);
  EXPECT_NEAR(m.closed_s, 2.0, 1e-6);  // simulated time: the epoch is taken off
  const core::Pose2 residual = core::Between(m.true_origin, m.placed_origin);
  EXPECT_NEAR(residual.x_m, 0.0, 1e-6);
  EXPECT_NEAR(residual.y_m, 0.0, 1e-6);
  EXPECT_NEAR(residual.theta_rad, 0.0, 1e-9);
  const core::Pose2 uncorrected =
      core::Between(m.true_origin, anchor * map.grid.geometry().origin());
  EXPECT_GT(std::hypot(uncorrected.x_m, uncorrected.y_m), 0.05);  // the test checks something

  EXPECT_EQ(run->run.final_map.state({100, 60}), core::CellState::kOccupied);
  EXPECT_EQ(run->fleet.final_version, 1);
  // First tile at 10.0 s, the last vehicle (beta) reports version 1 at 10.9 s.
  ASSERT_EQ(run->fleet.change_latency_s.size(), 1u);
  EXPECT_NEAR(run->fleet.change_latency_s[0], 0.9, 1e-6);
  EXPECT_EQ(run->fleet.changes_not_everywhere, 0);
  EXPECT_EQ(run->fleet.malformed_messages, 1);
  EXPECT_EQ(run->fleet.traffic.at(lcmtypes::PoseChannel("beta")).messages, 2);
  ASSERT_EQ(run->run.divergence.size(), 1u);
  EXPECT_NEAR(run->run.divergence[0].t_s, 1.5, 1e-6);
  EXPECT_TRUE(run->run.divergence[0].building);
  EXPECT_FALSE(run->run.poses.empty());

  const auto pairs = FleetJsonPairs(run->fleet);
  auto find = [&](const std::string& key) {
    for (const auto& [k, v] : pairs)
      if (k == key) return v;
    return std::string("missing");
  };
  EXPECT_EQ(find("fleet.change_latency_s.median"), "0.9");
  EXPECT_EQ(find("fleet.vehicles_holding_final_version"), "2");
}

TEST_F(RecordedRunTest, AVehicleThatNeverHoldsTheChangeIsCounted) {
  {
    lcm::LogFile log(path_, "w");
    core::TempMap map;
    map.vehicle_id = "beta";
    map.sequence = 1;
    map.anchor_in_map = world_->VehicleStateAt(1, 0.5).pose;
    map.grid = core::OccupancyGrid(core::GridGeometry(0.05, 20, 20));
    map.start_s = kEpoch + 0.5;
    map.end_s = kEpoch + 1.0;
    for (const core::TempMapTile& t : core::SplitTempMap(map))
      Log(log, 5.0, lcmtypes::TempMapChannel("beta"), lcmtypes::ToMessage(t, 0));
    fleetmap::merge_report_t r{};
    r.vehicle_id = "beta";
    r.tempmap_seq = 1;
    r.accepted = true;
    r.new_version = 1;
    Log(log, 5.1, lcmtypes::kMergeReportChannel, r);
    Log(log, 5.5, lcmtypes::PoseChannel("alpha"), Pose("alpha", 1.5, 1));
    Log(log, 5.6, lcmtypes::PoseChannel("beta"), Pose("beta", 1.5, 0));
  }
  auto run = ReadRecordedRun({path_}, *world_, Options());
  ASSERT_TRUE(run.ok()) << run.status().ToString();
  EXPECT_TRUE(run->fleet.change_latency_s.empty());
  EXPECT_EQ(run->fleet.changes_not_everywhere, 1);
}

// A recorded delta that decodes but does not fit the map (a tile beyond its edge) makes the
// replica drop its map; the run is read on, and the map recorded before stays the last one.
TEST_F(RecordedRunTest, ADeltaThatDoesNotFitTheMapIsNotRecordedAsAVersion) {
  const core::GridGeometry& room = world_->static_map().geometry();
  const core::OccupancyGrid before(core::GridGeometry(0.05, room.width() + 128, room.height()));
  core::OccupancyGrid after = before;
  after.SetState({room.width() + 100, 10}, core::CellState::kOccupied);
  const std::vector<core::EncodedTile> tiles = core::EncodeChangedTiles(before, after);
  ASSERT_EQ(tiles.size(), 1u);
  {
    lcm::LogFile log(path_, "w");
    LogDelta(log, 5.0, tiles[0]);
    Log(log, 5.5, lcmtypes::PoseChannel("alpha"), Pose("alpha", 1.5, 0));
  }
  auto run = ReadRecordedRun({path_}, *world_, Options());
  ASSERT_TRUE(run.ok()) << run.status().ToString();
  EXPECT_EQ(run->fleet.final_version, 0);
  EXPECT_EQ(run->run.final_map.geometry(), room);
  EXPECT_EQ(run->run.final_map.cells(), world_->static_map().cells());
}

// Two agents' STATUS over 20 s of wall clock and 40 simulated seconds (the simulator at 2x):
// alpha used 2 s of CPU (10 % of one core; 5 % in real time), beta 4 s (20 %; 10 %).
TEST_F(RecordedRunTest, AgentCpuAndMemoryComeFromTheirStatus) {
  auto status = [](const std::string& id, int64_t cpu_us, int64_t rss_kb) {
    fleetmap::status_t s{};
    s.process = "agent_" + id;
    s.counter_names = {"scans", "cpu_time_us", "rss_kb"};
    s.counter_values = {7, cpu_us, rss_kb};
    s.num_counters = 3;
    return s;
  };
  {
    lcm::LogFile log(path_, "w");
    Log(log, 0.0, "STATUS_agent_alpha", status("alpha", 1'000'000, 20'000));
    Log(log, 0.0, "STATUS_agent_beta", status("beta", 500'000, 30'000));
    Log(log, 10.0, "STATUS_agent_alpha", status("alpha", 2'000'000, 25'600));
    Log(log, 20.0, "STATUS_agent_alpha", status("alpha", 3'000'000, 24'000));
    Log(log, 20.0, "STATUS_agent_beta", status("beta", 4'500'000, 30'000));
    Log(log, 20.0, "STATUS_aggregator", status("x", 99'000'000, 900'000));  // not an agent
  }
  RecordedRunOptions options;
  options.epoch_s = kEpoch;
  options.duration_s = 40.0;
  auto run = ReadRecordedRun({path_}, *world_, options);
  ASSERT_TRUE(run.ok()) << run.status().ToString();
  ASSERT_EQ(run->fleet.agent_usage.size(), 2u);
  std::map<std::string, double> figures;
  for (const auto& [k, v] : FleetJsonPairs(run->fleet)) figures[k] = std::atof(v.c_str());
  EXPECT_NEAR(figures["agent.cpu_percent"], 15.0, 1e-6);
  EXPECT_NEAR(figures["agent.cpu_percent_realtime"], 7.5, 1e-6);
  EXPECT_NEAR(figures["agent.rss_mb"], 30'000 / 1024.0, 1e-3);
  EXPECT_NE(FleetFigureLines(run->fleet).find("agent.cpu_percent 15 %"), std::string::npos)
      << FleetFigureLines(run->fleet);
}

TEST(RecordedRunErrorsTest, MissingOrEmptyLogsAreErrors) {
  const sim::World world =
      sim::World::Create(sim::ParseScenario(kScenario, "s.yaml").value(), sim::testing::Room())
          .value();
  EXPECT_FALSE(ReadRecordedRun({}, world, {}).ok());
  auto missing = ReadRecordedRun({"/nonexistent/run.lcmlog"}, world, {});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().ToString().find("/nonexistent/run.lcmlog"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::eval::recording
