#include "eval/recording/recorded_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>

#include "auth/signer.h"
#include "core/codec/temp_map_tiles.h"
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"
#include "sim/scenario.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::eval::recording {
namespace {

constexpr const char* kScenario = R"(
map: room.yaml
duration_s: 5
vehicles:
  - {id: alpha, route: [[1, 3], [4, 3]]}
  - {id: beta, route: [[1, 2], [4, 2]]}
)";
constexpr double kEpoch = 1000.0;  // what fleetmap-sim added to simulated time
constexpr int64_t kWall0 = 1'700'000'000'000'000;

// Writes a small recorded run: one temporary map of alpha, its merge, the delta that carries
// it, and both vehicles' poses reporting the new version at different times.
class RecordedRunTest : public ::testing::Test {
 protected:
  void SetUp() override {
    world_.emplace(
        sim::World::Create(sim::ParseScenario(kScenario, "s.yaml").value(), sim::testing::Room())
            .value());
    path_ = (std::filesystem::temp_directory_path() /
             ("recorded_run_test_" + std::to_string(::getpid()) + ".lcmlog"))
                .string();
  }
  void TearDown() override { std::filesystem::remove(path_); }

  // Logs `msg` as its channel's owner sends it: with the trailer that names the sender
  // (signed with `key_` when set).
  template <typename Msg>
  void Log(lcm::LogFile& log, double wall_s, const std::string& channel, const Msg& msg) {
    LogAs(log, wall_s, channel, msg, Owner(channel));
  }
  template <typename Msg>
  void LogAs(lcm::LogFile& log, double wall_s, const std::string& channel, const Msg& msg,
             const std::string& sender) {
    std::vector<uint8_t> data = Encode(msg);
    Signer(sender).Seal(channel, data);
    LogBytes(log, wall_s, channel, data);
  }
  template <typename Msg>
  static std::vector<uint8_t> Encode(const Msg& msg) {
    std::vector<uint8_t> data(msg.getEncodedSize());
    msg.encode(data.data(), 0, static_cast<int>(data.size()));
    return data;
  }
  static std::string Owner(const std::string& channel) {
    return lcmtypes::ChannelOwner(channel, "aggregator").value();
  }
  auth::Signer& Signer(const std::string& sender) {
    auto it = signers_.find(sender);
    if (it == signers_.end()) it = signers_.emplace(sender, auth::Signer(key_, sender, 1)).first;
    return it->second;
  }
  RecordedRunOptions Options() const {
    RecordedRunOptions options;
    options.epoch_s = kEpoch;
    return options;
  }
  void LogBytes(lcm::LogFile& log, double wall_s, const std::string& channel,
                std::vector<uint8_t> data) {
    lcm::LogEvent e;
    e.eventnum = events_++;
    e.timestamp = kWall0 + static_cast<int64_t>(wall_s * 1e6);
    e.channel = channel;
    e.datalen = static_cast<int32_t>(data.size());
    e.data = data.data();
    ASSERT_EQ(log.writeEvent(&e), 0);
    last_bytes_[channel] = std::move(data);
  }
  // Version 0 -> 1 as one MAP_DELTA tile.
  void LogDelta(lcm::LogFile& log, double wall_s, const core::EncodedTile& tile) {
    core::DeltaTile delta;
    delta.base_version = 0;
    delta.index = 0;
    delta.count = 1;
    delta.tile = tile.index;
    delta.frame = tile.frame;
    Log(log, wall_s, lcmtypes::kMapDeltaChannel, lcmtypes::ToMessage(delta, 0));
  }
  fleetmap::pose_with_covariance_t Pose(const std::string& id, double t_s, int version) {
    core::PoseEstimate p;
    p.stamp_s = kEpoch + t_s;
    p.pose_in_map = world_->VehicleStateAt(id == "alpha" ? 0 : 1, t_s).pose;
    p.covariance = Eigen::Matrix3d::Identity() * 1e-4;
    p.map_version = version;
    return lcmtypes::ToMessage(p, id);
  }

  // The anchor of alpha's temporary map: its true pose with a localization error.
  core::Pose2 MergeRunAnchor() const {
    return world_->VehicleStateAt(0, 1.0).pose * core::Pose2(0.10, -0.05, 0.01);
  }
  core::TempMap MergeRunMap() const {
    core::TempMap map;
    map.vehicle_id = "alpha";
    map.sequence = 3;
    map.anchor_in_map = MergeRunAnchor();
    map.grid = core::OccupancyGrid(core::GridGeometry(0.05, 40, 30, core::Pose2(-1.0, -0.75, 0)));
    map.start_s = kEpoch + 1.0;
    map.end_s = kEpoch + 2.0;
    return map;
  }
  // One temporary map of alpha, its merge (the correction moves the anchor exactly onto the
  // truth), the delta that carries it (cell 100, 60 occupied), alpha's divergence, both
  // vehicles' poses reporting the new version at different times, and a garbage report.
  void WriteMergeRun(lcm::LogFile& log) {
    const core::Pose2 truth = world_->VehicleStateAt(0, 1.0).pose;
    const core::Pose2 anchor = MergeRunAnchor();
    const core::Pose2 correction(truth.x_m - anchor.x_m, truth.y_m - anchor.y_m,
                                 truth.theta_rad - anchor.theta_rad);
    core::OccupancyGrid changed = world_->static_map();
    changed.SetState({100, 60}, core::CellState::kOccupied);
    const std::vector<core::EncodedTile> tiles =
        core::EncodeChangedTiles(world_->static_map(), changed);
    ASSERT_EQ(tiles.size(), 1u);
    for (const core::TempMapTile& t : core::SplitTempMap(MergeRunMap()))
      Log(log, 10.0, lcmtypes::TempMapChannel("alpha"), lcmtypes::ToMessage(t, 0));
    fleetmap::divergence_t d{};
    d.utime = lcmtypes::ToUtime(kEpoch + 1.5);
    d.vehicle_id = "alpha";
    d.d = 0.4;
    d.state = fleetmap::divergence_t::BUILDING;
    Log(log, 10.1, lcmtypes::DivergenceChannel("alpha"), d);
    Log(log, 10.2, lcmtypes::kMergeReportChannel, Report(correction, true, 1));
    report_bytes_ = last_bytes_.at(lcmtypes::kMergeReportChannel);
    LogDelta(log, 10.3, tiles[0]);
    Log(log, 10.4, lcmtypes::PoseChannel("alpha"), Pose("alpha", 2.5, 1));
    Log(log, 10.5, lcmtypes::PoseChannel("beta"), Pose("beta", 2.5, 0));
    Log(log, 10.9, lcmtypes::PoseChannel("beta"), Pose("beta", 3.0, 1));
    std::vector<uint8_t> garbage = {1, 2, 3};  // the aggregator's, but not a message
    Signer("aggregator").Seal(lcmtypes::kMergeReportChannel, garbage);
    LogBytes(log, 11.0, lcmtypes::kMergeReportChannel, garbage);
  }
  static fleetmap::merge_report_t Report(const core::Pose2& correction, bool accepted,
                                         int32_t new_version) {
    fleetmap::merge_report_t r{};
    r.vehicle_id = "alpha";
    r.tempmap_seq = 3;
    r.accepted = accepted;
    r.dx_m = correction.x_m;
    r.dy_m = correction.y_m;
    r.dtheta_rad = correction.theta_rad;
    r.cells_added = 1;
    r.new_version = new_version;
    return r;
  }

  // What another fleet, a test tool or a copy of an old message puts on the same channels,
  // each of which would change a figure if it were believed: a report rejecting alpha's map
  // and a delta setting another cell, neither naming a sender; a report and a pose naming
  // the wrong sender; the aggregator's report logged again; garbage naming no sender.
  void WriteForeignTraffic(lcm::LogFile& log) {
    LogBytes(log, 10.25, lcmtypes::kMergeReportChannel, Encode(Report(core::Pose2(), false, 0)));
    core::OccupancyGrid other = world_->static_map();
    other.SetState({50, 50}, core::CellState::kOccupied);
    const auto tiles = core::EncodeChangedTiles(world_->static_map(), other);
    core::DeltaTile delta;
    delta.base_version = 0;
    delta.count = 1;
    delta.tile = tiles.at(0).index;
    delta.frame = tiles.at(0).frame;
    LogBytes(log, 10.26, lcmtypes::kMapDeltaChannel, Encode(lcmtypes::ToMessage(delta, 0)));
    LogAs(log, 10.27, lcmtypes::kMergeReportChannel, Report(core::Pose2(1, 1, 0), true, 2),
          "aggregator-test");
    LogAs(log, 10.45, lcmtypes::PoseChannel("beta"), Pose("beta", 2.6, 1), "alpha");
    LogBytes(log, 10.6, lcmtypes::kMergeReportChannel, report_bytes_);
    LogBytes(log, 10.7, lcmtypes::kMapKeyframeChannel, {9, 9, 9});
  }

  std::optional<sim::World> world_;
  std::string path_;
  int64_t events_ = 0;
  std::optional<auth::Key> key_;  // the fleet's key; none: identity trailers
  std::map<std::string, auth::Signer> signers_;
  std::map<std::string, std::vector<uint8_t>> last_bytes_;  // by channel, as logged
  std::vector<uint8_t> report_bytes_;                       // the merge of WriteMergeRun
};

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

// Traffic that is not the aggregator's (or the vehicle's) on the fleet's channels is left out:
// the run scores exactly as without it, and each refusal is counted by its reason.
TEST_F(RecordedRunTest, ForeignTrafficOnTheFleetsChannelsChangesNoFigure) {
  auto read = [&](bool foreign) {
    signers_.clear();
    {
      lcm::LogFile log(path_, "w");
      WriteMergeRun(log);
      if (foreign) WriteForeignTraffic(log);
    }
    return ReadRecordedRun({path_}, *world_, Options());
  };
  auto clean = read(false);
  auto mixed = read(true);
  ASSERT_TRUE(clean.ok()) << clean.status().ToString();
  ASSERT_TRUE(mixed.ok()) << mixed.status().ToString();

  ASSERT_EQ(mixed->run.merges.size(), 1u);
  EXPECT_TRUE(mixed->run.merges[0].accepted);
  EXPECT_EQ(mixed->run.final_map.state({100, 60}), core::CellState::kOccupied);
  EXPECT_EQ(mixed->run.final_map.cells(), clean->run.final_map.cells());
  std::map<std::string, std::string> clean_figures, mixed_figures;
  for (const auto& [k, v] : FleetJsonPairs(clean->fleet)) clean_figures[k] = v;
  for (const auto& [k, v] : FleetJsonPairs(mixed->fleet))
    if (k.rfind("fleet.messages_refused", 0) != 0) mixed_figures[k] = v;
  EXPECT_EQ(clean_figures.at("fleet.messages_refused"), "0");
  clean_figures.erase("fleet.messages_refused");
  EXPECT_EQ(mixed_figures, clean_figures);
  EXPECT_EQ(mixed->fleet.messages_refused,
            (std::map<std::string, int>{{"unnamed", 3}, {"wrong_sender", 2}, {"replayed", 1}}));
  EXPECT_NE(FleetFigureLines(mixed->fleet).find("fleet.messages_refused 6 count"),
            std::string::npos);
}

// With the fleet key, a message counts only if its MAC is right: the name alone (an identity
// trailer) or another fleet's key is refused; read with a wrong key, nothing can be scored.
TEST_F(RecordedRunTest, WithTheFleetKeyOnlyWhatItsMacVerifiesIsRead) {
  key_ = auth::GenerateKey();
  {
    lcm::LogFile log(path_, "w");
    WriteMergeRun(log);
    std::vector<uint8_t> named = Encode(Report(core::Pose2(), false, 0));
    auth::Signer(std::nullopt, "aggregator", 1u << 20).Seal(lcmtypes::kMergeReportChannel, named);
    LogBytes(log, 10.25, lcmtypes::kMergeReportChannel, named);
    std::vector<uint8_t> forged = Encode(Report(core::Pose2(), false, 0));
    auth::Signer(auth::GenerateKey(), "aggregator", 1u << 21)
        .Seal(lcmtypes::kMergeReportChannel, forged);
    LogBytes(log, 10.26, lcmtypes::kMergeReportChannel, forged);
  }
  RecordedRunOptions options = Options();
  options.fleet_key = key_;
  auto run = ReadRecordedRun({path_}, *world_, options);
  ASSERT_TRUE(run.ok()) << run.status().ToString();
  ASSERT_EQ(run->run.merges.size(), 1u);
  EXPECT_TRUE(run->run.merges[0].accepted);
  EXPECT_EQ(run->fleet.messages_refused,
            (std::map<std::string, int>{{"forged", 1}, {"unsigned", 1}}));

  options.fleet_key = auth::GenerateKey();
  auto wrong_key = ReadRecordedRun({path_}, *world_, options);
  ASSERT_FALSE(wrong_key.ok());
  EXPECT_EQ(wrong_key.status().code(), core::StatusCode::kFailedPrecondition);
  EXPECT_NE(wrong_key.status().ToString().find("key"), std::string::npos);
}

// A log of processes that name no sender (or of another system on the same channels) has
// nothing the evaluation may believe: an error, never a run scored over nothing.
TEST_F(RecordedRunTest, ALogWhereNoMessageNamesItsSenderIsAnError) {
  {
    lcm::LogFile log(path_, "w");
    LogBytes(log, 5.0, lcmtypes::kMergeReportChannel, Encode(Report(core::Pose2(), true, 1)));
    LogBytes(log, 5.5, lcmtypes::PoseChannel("alpha"), Encode(Pose("alpha", 1.5, 0)));
  }
  auto run = ReadRecordedRun({path_}, *world_, Options());
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.status().code(), core::StatusCode::kFailedPrecondition);
  EXPECT_NE(run.status().ToString().find("2 messages"), std::string::npos)
      << run.status().ToString();
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
