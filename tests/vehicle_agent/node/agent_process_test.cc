// The fleetmap-agent binary over real LCM UDP multicast on loopback: simulated SCAN_/ODOM_
// published on its sensor link, POSE_ and STATUS_ read on its uplink, stopped with SIGINT.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <thread>

#include "auth/trailer.h"
#include "core/map/map_io.h"
#include "tests/support/multicast.h"
#include "tests/support/process.h"
#include "tests/support/scratch_folder.h"
#include "tests/vehicle_agent/node/node_test_util.h"
#include "tests/vehicle_agent/node/sensor_feed.h"

namespace fleetmap::vehicle_agent::node {
namespace {

// Group and ports of this test only (other tests use other ones).
std::string Url(int group, int port) {
  return "udpm://239.255.77." + std::to_string(group) + ":" + std::to_string(port) +
         "?ttl=0&recv_buf_size=8388608";
}

using fleetmap::testing::Process;
using fleetmap::testing::ReadText;
using fleetmap::testing::RunToExit;

class Uplink {
 public:
  void OnPose(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    auto m = lcmtypes::Decode<fleetmap::pose_with_covariance_t>(
        rbuf->data, int(auth::PayloadSize(rbuf->data, rbuf->data_size)));
    ASSERT_TRUE(m.ok());
    poses.push_back(*m);
  }
  void OnStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    auto m = lcmtypes::Decode<fleetmap::status_t>(
        rbuf->data, int(auth::PayloadSize(rbuf->data, rbuf->data_size)));
    ASSERT_TRUE(m.ok());
    status.push_back(*m);
  }
  std::vector<fleetmap::pose_with_covariance_t> poses;
  std::vector<fleetmap::status_t> status;
};

TEST(AgentProcessTest, LocalizesOverMulticastAndStopsCleanlyOnSigint) {
  const std::string sensor = Url(41, 7941), uplink = Url(42, 7942), downlink = Url(43, 7943);
  FLEETMAP_REQUIRE_MULTICAST(sensor);
  fleetmap::testing::ScratchFolder dir;
  const sim::World world = testing::RoomWorld();
  ASSERT_TRUE(core::SaveMapServerMap(world.static_map(), dir.File("room.yaml")).ok());
  lcm::LCM sensor_lcm(sensor), uplink_lcm(uplink);
  ASSERT_TRUE(sensor_lcm.good() && uplink_lcm.good());
  Uplink received;
  uplink_lcm.subscribe("POSE_v1", &Uplink::OnPose, &received);
  uplink_lcm.subscribe("STATUS_agent_v1", &Uplink::OnStatus, &received);

  const core::Pose2 start = world.VehicleStateAt(0, 0.0).pose;
  const std::string pose = std::to_string(start.x_m) + "," + std::to_string(start.y_m) + "," +
                           std::to_string(start.theta_rad);
  Process agent({FLEETMAP_AGENT_BINARY,
                 "--vehicle-id",
                 "v1",
                 "--map",
                 dir.File("room.yaml"),
                 "--initial-pose",
                 pose,
                 "--scanner-mount",
                 "0.3,0,0",
                 "--sensor-url",
                 sensor,
                 "--uplink-url",
                 uplink,
                 "--downlink-url",
                 downlink,
                 "--state-dir",
                 dir.File("state"),
                 "--final-map",
                 dir.File("final.yaml"),
                 "--quiet"},
                dir.File("out.txt"), dir.File("err.txt"));
  ASSERT_TRUE(agent.started());
  // The agent is up once its first heartbeat arrives (deadline only against a hang).
  for (int i = 0; i < 200 && received.status.empty(); ++i) uplink_lcm.handleTimeout(50);
  ASSERT_FALSE(received.status.empty()) << ReadText(dir.File("err.txt"));

  // 16 simulated seconds at 4x.
  const std::map<int64_t, core::Pose2> truth = testing::PublishSensors(sensor_lcm, world, 4.0, [&] {
    while (uplink_lcm.handleTimeout(0) > 0) {
    }
  });
  for (int i = 0; i < 10; ++i) uplink_lcm.handleTimeout(50);  // the last poses
  agent.Signal(SIGINT);
  EXPECT_EQ(agent.Wait(20.0), 0) << ReadText(dir.File("err.txt"));
  while (uplink_lcm.handleTimeout(200) > 0) {  // its last STATUS, sent at exit
  }

  // Every scan was localized or, when the agent fell behind (a busy machine), skipped and
  // counted: the exit STATUS accounts for all of them.
  const fleetmap::status_t& last = received.status.back();
  EXPECT_EQ(last.process, "agent_v1");
  EXPECT_EQ(last.state, "running");
  EXPECT_EQ(last.map_version, 0);
  std::map<std::string, int64_t> counters;
  for (int i = 0; i < last.num_counters; ++i)
    counters[last.counter_names[i]] = last.counter_values[i];
  EXPECT_EQ(counters["scans"] + counters["scans_skipped"], static_cast<int64_t>(truth.size()));
  EXPECT_EQ(counters["malformed_messages"], 0);
  EXPECT_GE(received.status.size(), 4u);  // about one per second
  // The poses: on version 0, where the vehicle was.
  ASSERT_GT(received.poses.size(), truth.size() / 2);
  int close = 0;
  for (const auto& p : received.poses) {
    EXPECT_EQ(p.vehicle_id, "v1");
    EXPECT_EQ(p.map_version, 0);
    ASSERT_TRUE(truth.count(p.utime));
    const core::Pose2& t = truth.at(p.utime);
    close += std::hypot(p.pose.x_m - t.x_m, p.pose.y_m - t.y_m) < 0.05;
  }
  EXPECT_GT(close, static_cast<int>(received.poses.size()) * 9 / 10);
  // The final line and the final map.
  const std::string out = ReadText(dir.File("out.txt"));
  EXPECT_EQ(out.rfind("agent v1: scans ", 0), 0u) << out;
  EXPECT_NE(out.find(" map_version 0 tempmaps 0"), std::string::npos) << out;
  auto final_map = core::LoadMapServerMap(dir.File("final.yaml"));
  ASSERT_TRUE(final_map.ok()) << final_map.status().ToString();
  EXPECT_EQ(final_map->grid.geometry().width(), world.static_map().geometry().width());
}

TEST(AgentProcessTest, BadFlagsAndAMissingMapFailWithAClearMessage) {
  fleetmap::testing::ScratchFolder dir;
  // Output is appended: each run writes files of its own.
  EXPECT_EQ(
      RunToExit({FLEETMAP_AGENT_BINARY, "--vehicle-id", "v 1"}, dir.File("o1"), dir.File("e1"), 20),
      2);
  EXPECT_NE(ReadText(dir.File("e1")).find("vehicle_id"), std::string::npos);
  EXPECT_EQ(RunToExit({FLEETMAP_AGENT_BINARY, "--vehicle-id", "v1", "--initial-pose", "1,2"},
                      dir.File("o2"), dir.File("e2"), 20),
            2);
  EXPECT_NE(ReadText(dir.File("e2")).find("X,Y,THETA"), std::string::npos);
  EXPECT_EQ(RunToExit({FLEETMAP_AGENT_BINARY, "--vehicle-id", "v1", "--map", dir.File("none.yaml")},
                      dir.File("o3"), dir.File("e3"), 20),
            1);
  EXPECT_NE(ReadText(dir.File("e3")).find("none.yaml"), std::string::npos);
  EXPECT_EQ(RunToExit({FLEETMAP_AGENT_BINARY, "--help"}, dir.File("o4"), dir.File("e4"), 20), 0);
  EXPECT_NE(ReadText(dir.File("o4")).find("--initial-pose"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
