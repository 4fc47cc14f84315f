// The last good pose in the state folder: a restart on a vehicle that has not moved starts
// there; one that moved meanwhile does not, and finds itself by a search of the map.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "tests/support/scratch_folder.h"
#include "tests/vehicle_agent/node/node_test_util.h"
#include "vehicle_agent/node/agent_node.h"
#include "vehicle_agent/node/pose_store.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

struct Started {
  std::unique_ptr<AgentNode> node;
  std::vector<std::string> log;
};

Started Start(const AgentNodeOptions& options, RecordingPublisher* out, const sim::World& world) {
  Started s;
  auto* log = &s.log;
  auto node = AgentNode::Create(
      options, out, [log](LogLevel, const std::string& line) { log->push_back(line); },
      world.static_map(), 0.0);
  EXPECT_TRUE(node.ok()) << node.status().ToString();
  s.node = std::move(node).value();
  return s;
}

bool Logged(const std::vector<std::string>& log, const std::string& part) {
  for (const std::string& line : log)
    if (line.find(part) != std::string::npos) return true;
  return false;
}

// The test room with a cupboard in one corner, so that no other pose looks the same.
sim::World RoomWithCupboard() {
  const std::string yaml =
      "map: room.yaml\nduration_s: 30\nseed: 5\nvehicles:\n  - {id: v1, route: [[1.5, 2.0], "
      "[8.5, 2.0]], speed_mps: 0.5, scanner_mount: [0.3, 0.0, 0.0]}\n";
  auto scenario = sim::ParseScenario(yaml, "room_scenario.yaml");
  EXPECT_TRUE(scenario.ok()) << scenario.status().ToString();
  core::OccupancyGrid map = sim::testing::Room();
  for (int y = 90; y < 118; ++y)
    for (int x = 160; x < 198; ++x) map.SetState({x, y}, core::CellState::kOccupied);
  auto world = sim::World::Create(std::move(scenario).value(), std::move(map));
  EXPECT_TRUE(world.ok()) << world.status().ToString();
  return std::move(world).value();
}

// The first published pose, and how far it is from the truth then.
double FirstPoseError(RecordingPublisher& out, const std::map<int64_t, core::Pose2>& truth) {
  const auto poses = out.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1");
  if (poses.empty()) return 1e9;
  const core::Pose2& t = truth.at(poses.front().utime);
  return std::hypot(poses.front().pose.x_m - t.x_m, poses.front().pose.y_m - t.y_m);
}

TEST(LastPoseTest, ARestartWhereTheVehicleStoodStartsFromItsLastPose) {
  const sim::World world = testing::RoomWorld("[]", 30.0);
  fleetmap::testing::ScratchFolder dir;
  {
    RecordingPublisher out;
    Started first = Start(testing::RoomOptions(world, dir.path()), &out, world);
    testing::DriveNode(world, *first.node, 6.0);
    first.node->Shutdown(6.0);
  }
  auto kept = PoseStore(dir.path()).Load();
  ASSERT_TRUE(kept.ok()) << kept.status().ToString();
  EXPECT_NEAR(kept->base_in_map.x_m, world.VehicleStateAt(0, 6.0).pose.x_m, 0.1);

  // Restarted at 6 s with a given pose 2.5 m behind: the kept pose wins, from the first scan.
  RecordingPublisher out;
  Started second = Start(testing::RoomOptions(world, dir.path()), &out, world);
  const auto truth = testing::DriveNode(world, *second.node, 8.0, {}, 6.0);
  EXPECT_LT(FirstPoseError(out, truth), 0.1);
  EXPECT_EQ(testing::Counter(*second.node, "starts_from_last_pose"), 1);
  EXPECT_TRUE(Logged(second.log, "starting from the last pose kept in")) << second.log.size();
}

TEST(LastPoseTest, AVehicleThatMovedMeanwhileDoesNotUseItAndFindsItself) {
  const sim::World world = RoomWithCupboard();
  fleetmap::testing::ScratchFolder dir;
  {
    RecordingPublisher out;
    Started first = Start(testing::RoomOptions(world, dir.path()), &out, world);
    testing::DriveNode(world, *first.node, 4.0);
    first.node->Shutdown(4.0);
  }
  // Back at 9 s: 2.5 m further on than the kept pose, and given a pose across the room,
  // turned, whose beams would go through the walls.
  RecordingPublisher out;
  AgentNodeOptions options = testing::RoomOptions(world, dir.path());
  options.pipeline.localizer.initial_pose_in_map = core::Pose2(3.0, 4.5, 2.0);
  Started second = Start(options, &out, world);
  const auto truth = testing::DriveNode(world, *second.node, 18.0, {}, 9.0);
  EXPECT_EQ(testing::Counter(*second.node, "starts_from_last_pose"), 0);
  EXPECT_TRUE(Logged(second.log, "last pose not used: the odometry moved"));
  EXPECT_GT(FirstPoseError(out, truth), 2.0);  // the given pose
  // The map does not explain the scans from there: lost, searched, found.
  EXPECT_GE(testing::Counter(*second.node, "relocalizations"), 1);
  EXPECT_TRUE(Logged(second.log, "lost: the map has not explained the scans"));
  EXPECT_TRUE(Logged(second.log, "localized again"));
  const auto poses = out.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1");
  ASSERT_FALSE(poses.empty());
  const core::Pose2& t = truth.at(poses.back().utime);
  EXPECT_LT(std::hypot(poses.back().pose.x_m - t.x_m, poses.back().pose.y_m - t.y_m), 0.1);
}

TEST(LastPoseTest, AFileThatIsNotAKeptPoseIsSaidAndIgnored) {
  const sim::World world = testing::RoomWorld();
  fleetmap::testing::ScratchFolder dir;
  std::ofstream(dir.File("last_pose")) << "fleetmap-last-pose-1 1 2 nan 0 0 0 3\n";
  EXPECT_EQ(PoseStore(dir.path()).Load().status().code(), core::StatusCode::kDataLoss);
  RecordingPublisher out;
  Started s = Start(testing::RoomOptions(world, dir.path()), &out, world);
  const auto truth = testing::DriveNode(world, *s.node, 2.0);
  EXPECT_TRUE(Logged(s.log, "last pose not used")) << s.log.size();
  EXPECT_LT(FirstPoseError(out, truth), 0.1);  // the given pose, at the start of the route
}

TEST(PoseStoreTest, KeepsAPoseAndSaysWhenItStillHolds) {
  fleetmap::testing::ScratchFolder dir;
  const PoseStore store(dir.path());
  EXPECT_EQ(store.Load().status().code(), core::StatusCode::kNotFound);
  const KeptPose kept{core::Pose2(12.5, -3.25, 1.5), core::Pose2(100.0, 20.0, -0.5), 7};
  ASSERT_TRUE(store.Store(kept).ok());
  auto back = store.Load();
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_NEAR(back->base_in_map.y_m, -3.25, 1e-6);
  EXPECT_NEAR(back->odometry.theta_rad, -0.5, 1e-6);
  EXPECT_EQ(back->map_version, 7);
  const KeptPoseOptions o;
  EXPECT_TRUE(StillThere(kept, core::Pose2(100.01, 20.0, -0.505), o));
  EXPECT_FALSE(StillThere(kept, core::Pose2(100.05, 20.0, -0.5), o));
  EXPECT_FALSE(StillThere(kept, core::Pose2(100.0, 20.0, -0.45), o));
  EXPECT_FALSE(StillThere(kept, core::Pose2(), o));  // odometry that restarted with the vehicle
  std::ofstream(dir.File("last_pose")) << "fleetmap-last-pose-1 1 2 3 4 5 6 7 extra\n";
  EXPECT_EQ(store.Load().status().code(), core::StatusCode::kDataLoss);
  EXPECT_FALSE(PoseStore("").enabled());
  KeptPoseOptions bad;
  bad.same_odometry_m = -1;
  EXPECT_FALSE(bad.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
