// In-memory harness for the agent node: a Publisher that records what the node sends, a
// small simulated world (the 10 m x 6 m room of the simulator tests) and a driver that feeds
// the simulator's scans and odometry to the node as encoded LCM messages.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "auth/trailer.h"
#include "core/codec/temp_map_tiles.h"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"
#include "sim/simulator.h"
#include "tests/edge/recording_publisher.h"
#include "tests/sim/sim_test_util.h"
#include "vehicle_agent/node/agent_messages.h"
#include "vehicle_agent/node/agent_node.h"

namespace fleetmap::vehicle_agent::node::testing {

using edge::testing::RecordingPublisher;
using edge::testing::SentMessage;

// One vehicle "v1" crossing the room; `objects` is YAML for the scenario's objects list.
inline sim::World RoomWorld(const std::string& objects = "[]", double duration_s = 16.0) {
  const std::string yaml = "map: room.yaml\nduration_s: " + std::to_string(duration_s) +
                           "\nseed: 5\nobjects: " + objects +
                           "\nvehicles:\n  - {id: v1, route: [[1.5, 2.0], [8.5, 2.0]], "
                           "speed_mps: 0.5, scanner_mount: [0.3, 0.0, 0.0]}\n";
  auto scenario = sim::ParseScenario(yaml, "room_scenario.yaml");
  if (!scenario.ok()) throw std::runtime_error(scenario.status().ToString());
  auto world = sim::World::Create(std::move(scenario).value(), sim::testing::Room());
  if (!world.ok()) throw std::runtime_error(world.status().ToString());
  return std::move(world).value();
}

// A pallet that appears in front of the vehicle's path at 3 s.
inline const char* kPallet =
    "[{id: pallet, rect: {center: [5.5, 4.2], size: [1.2, 0.8]}, appear_s: 3}]";

inline AgentNodeOptions RoomOptions(const sim::World& world, const std::string& state_dir = "") {
  AgentNodeOptions o;
  o.pipeline.vehicle_id = "v1";
  o.pipeline.scanner_in_base = world.scenario().vehicles[0].scanner_mount;
  o.pipeline.localizer.initial_pose_in_map = world.VehicleStateAt(0, 0.0).pose;
  o.pipeline.localizer.initial_sigma_xy_m = 0.05;
  o.pipeline.localizer.initial_sigma_theta_rad = 0.02;
  // Maps opened by d(t) alone: the room's tests put their changes in view at known times.
  o.pipeline.divergence.map_at_start = false;
  o.outbox.state_dir = state_dir;
  o.software_version = "test";
  return o;
}

inline void Feed(AgentNode& node, Link link, const std::string& channel,
                 const std::vector<uint8_t>& bytes, double now_s) {
  node.OnMessage(link, channel, bytes.data(), static_cast<int>(bytes.size()), now_s);
}

template <typename T>
void FeedMessage(AgentNode& node, Link link, const std::string& channel, const T& message,
                 double now_s) {
  Feed(node, link, channel, Encode(message), now_s);
}

// Runs the world's simulator into the node (scans and odometry as SCAN_v1 / ODOM_v1
// messages), ticking after every scan with now = the scan's time. Returns the true pose of
// every scan by its utime.
// Events before `from_s` are skipped. `vehicle_clock` (if given) maps simulated time to the
// stamps the vehicle puts on its scans and odometry (a clock that jumps).
inline std::map<int64_t, core::Pose2> DriveNode(
    const sim::World& world, AgentNode& node, double until_s,
    const std::function<void(double t_s)>& after_tick = {}, double from_s = 0.0,
    const std::function<double(double t_s)>& vehicle_clock = {}) {
  const auto stamp = [&](double t) { return vehicle_clock ? vehicle_clock(t) : t; };
  std::map<int64_t, core::Pose2> truth;
  sim::Simulator simulator(&world);
  int32_t seq = 0;
  while (auto e = simulator.Next()) {
    const double t = sim::EventTime(*e);
    if (t > until_s) break;
    if (t < from_s) continue;
    if (const auto* o = std::get_if<sim::OdometryEvent>(&*e)) {
      const core::OdometrySample odom{stamp(o->stamp_s), o->odom_pose, o->v_mps, o->omega_radps};
      FeedMessage(node, Link::kSensor, "ODOM_v1", lcmtypes::ToMessage(odom, "v1"), t);
    } else if (const auto* s = std::get_if<sim::ScanEvent>(&*e)) {
      core::LaserScan scan = s->scan;
      scan.stamp_s = stamp(scan.stamp_s);
      FeedMessage(node, Link::kSensor, "SCAN_v1", lcmtypes::ToMessage(scan, "v1", seq++), t);
      truth[lcmtypes::ToUtime(scan.stamp_s)] = s->true_base_pose;
      node.Tick(t);
      if (after_tick) after_tick(t);
    }
  }
  return truth;
}

// Every tile of `grid` as the keyframe of `version` (64-cell tiles).
inline std::vector<core::KeyframeTile> KeyframeTiles(const core::OccupancyGrid& grid,
                                                     int32_t version) {
  std::vector<core::KeyframeTile> out;
  const auto tiles = core::EncodeAllTiles(grid);
  for (size_t i = 0; i < tiles.size(); ++i)
    out.push_back({version, grid.geometry(), 64, static_cast<int32_t>(i),
                   static_cast<int32_t>(tiles.size()), tiles[i].index, tiles[i].frame});
  return out;
}

// The same as MAP_KEYFRAME messages.
inline std::vector<fleetmap::map_keyframe_t> KeyframeMessages(const core::OccupancyGrid& grid,
                                                              int32_t version) {
  std::vector<fleetmap::map_keyframe_t> out;
  for (const core::KeyframeTile& k : KeyframeTiles(grid, version))
    out.push_back(lcmtypes::ToMessage(k, 0));
  return out;
}

// The change from `before` to `after` as MAP_DELTA messages from base_version.
inline std::vector<fleetmap::map_delta_t> DeltaMessages(const core::OccupancyGrid& before,
                                                        const core::OccupancyGrid& after,
                                                        int32_t base_version) {
  std::vector<fleetmap::map_delta_t> out;
  const auto tiles = core::EncodeChangedTiles(before, after);
  for (size_t i = 0; i < tiles.size(); ++i) {
    core::DeltaTile d{base_version, static_cast<int32_t>(i), static_cast<int32_t>(tiles.size()),
                      tiles[i].index, tiles[i].frame};
    out.push_back(lcmtypes::ToMessage(d, 0));
  }
  if (tiles.empty())
    out.push_back(lcmtypes::ToMessage(core::DeltaTile{base_version, 0, 0, {}, {}}, 0));
  return out;
}

inline int64_t Counter(const AgentNode& node, const std::string& name) {
  return CounterValue(node.AllCounters(), name);
}

}  // namespace fleetmap::vehicle_agent::node::testing
