// Recorded fleet runs written for the tests of ReadRecordedRun: a two-vehicle room scenario,
// and a fixture that logs messages as their channels' owners send them (with the trailer that
// names the sender, signed when the test sets a fleet key) or as raw bytes, into an LCM log of
// its own that it removes afterwards.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "auth/signer.h"
#include "core/codec/temp_map_tiles.h"
#include "eval/recording/recorded_run.h"
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"
#include "sim/scenario.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::eval::recording::testing {

// Two vehicles driving side by side across sim::testing::Room() for 5 s.
inline constexpr const char* kScenario = R"(
map: room.yaml
duration_s: 5
vehicles:
  - {id: alpha, route: [[1, 3], [4, 3]]}
  - {id: beta, route: [[1, 2], [4, 2]]}
)";
inline constexpr double kEpoch = 1000.0;  // what fleetmap-sim added to simulated time
inline constexpr int64_t kWall0 = 1'700'000'000'000'000;  // the log's wall clock at 0 s

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

}  // namespace fleetmap::eval::recording::testing
