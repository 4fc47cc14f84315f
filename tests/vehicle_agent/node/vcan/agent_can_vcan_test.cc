// The agent's CAN odometry input on a real kernel: needs a vcan interface named by
// FLEETMAP_VCAN and canplayer (FLEETMAP_CANPLAYER). ctest runs it through
// scripts/can_vm_test.sh (test agent_can_vcan_test), on a host vcan or inside a minimal qemu
// VM; run directly without those variables it skips and says why.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>

#include "drivers/can/candump_log.h"
#include "sim/can/sim_can_log.h"
#include "tests/vehicle_agent/node/node_test_util.h"
#include "vehicle_agent/node/can_odometry_input.h"

extern char** environ;

namespace fleetmap::vehicle_agent::node {
namespace {

std::string Env(const char* name) {
  const char* v = std::getenv(name);
  return v == nullptr ? "" : v;
}

TEST(AgentCanVcanTest, CanOdometryFromCanplayerDrivesTheAgent) {
  if (Env("FLEETMAP_VCAN").empty() || Env("FLEETMAP_CANPLAYER").empty()) {
    GTEST_SKIP() << "FLEETMAP_VCAN/FLEETMAP_CANPLAYER are not set: run through "
                    "scripts/can_vm_test.sh (ctest -R agent_can_vcan_test), which provides a vcan";
  }
  const sim::World world = testing::RoomWorld();
  sim::can::SimCanLogOptions log_options;
  log_options.duration_s = 6.0;
  auto log = sim::can::RecordOdometryAsCan(world, log_options);
  ASSERT_TRUE(log.ok()) << log.status().ToString();
  const std::string path = "/tmp/fleetmap_agent_vcan.log";
  ASSERT_TRUE(drivers::can::WriteCandumpLog(path, log->records).ok());

  CanInputOptions input_options;
  input_options.socket.interface = Env("FLEETMAP_VCAN");
  input_options.socket.receive_buffer_bytes = 8 << 20;
  input_options.odometry = log_options.can;
  auto input = CanOdometryInput::Open(input_options);
  ASSERT_TRUE(input.ok()) << input.status().ToString();

  // canplayer keeps the log's timing: the kernel stamps frames as a vehicle's bus would.
  std::vector<std::string> args = {Env("FLEETMAP_CANPLAYER"), "-I", path,
                                   Env("FLEETMAP_VCAN") + "=can0"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t player = -1;
  ASSERT_EQ(posix_spawn(&player, argv[0], nullptr, nullptr, argv.data(), environ), 0);
  std::vector<core::OdometrySample> samples;
  int status = 0;
  bool done = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    for (const core::OdometrySample& s : (*input)->Drain()) samples.push_back(s);
    if (done && samples.size() >= log->odometry.size()) break;
    if (!done && waitpid(player, &status, WNOHANG) == player) {
      done = true;
      for (int i = 0; i < 20; ++i) {  // what is still queued
        for (const core::OdometrySample& s : (*input)->Drain()) samples.push_back(s);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(done) << "canplayer did not finish";
  EXPECT_EQ(WEXITSTATUS(status), 0);
  ASSERT_EQ(samples.size(), log->odometry.size());
  const NamedCounters counters = (*input)->Counters();
  EXPECT_EQ(CounterValue(counters, "can_odometry_samples"), static_cast<int64_t>(samples.size()));
  EXPECT_EQ(CounterValue(counters, "can_kernel_drops"), 0);
  EXPECT_EQ(CounterValue(counters, "can_incomplete_cycles"), 0);

  // The agent: these samples as its odometry, the simulator's scans stamped in the same host
  // time (sample k is the simulator's odometry sample k, so their stamps give the offset).
  AgentNodeOptions options = testing::RoomOptions(world);
  options.scans_from_lcm = false;
  options.odometry_from_lcm = false;
  testing::RecordingPublisher out;
  auto node = AgentNode::Create(options, &out, nullptr, world.static_map(), 0.0).value();
  const double offset =
      samples.front().stamp_s - (log->odometry.front().stamp_s - log_options.start_time_s);
  std::map<int64_t, core::Pose2> truth;
  size_t next = 0;
  sim::Simulator simulator(&world);
  while (auto e = simulator.Next()) {
    const auto* scan = std::get_if<sim::ScanEvent>(&*e);
    if (scan == nullptr) continue;
    if (scan->scan.stamp_s > log_options.duration_s) break;
    core::LaserScan s = scan->scan;
    s.stamp_s += offset;
    while (next < samples.size() && samples[next].stamp_s <= s.stamp_s)
      node->OnDriverOdometry(samples[next++]);
    truth[lcmtypes::ToUtime(s.stamp_s)] = scan->true_base_pose;
    node->OnDriverScan(s);
    node->Tick(s.stamp_s);
  }
  std::vector<double> errors;
  for (const auto& p : out.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1")) {
    const core::Pose2& t = truth.at(p.utime);
    errors.push_back(std::hypot(p.pose.x_m - t.x_m, p.pose.y_m - t.y_m));
  }
  ASSERT_GT(errors.size(), 100u);
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.03);
  EXPECT_EQ(testing::Counter(*node, "odometry"), static_cast<int64_t>(next));
  EXPECT_EQ(testing::Counter(*node, "odometry_jumps"), 0);
  std::printf("agent over vcan: %zu CAN odometry samples, %zu poses, median error %.4f m\n",
              samples.size(), errors.size(), errors[errors.size() / 2]);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
