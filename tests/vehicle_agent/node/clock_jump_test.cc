// A vehicle whose clock jumps (docs/reliability.md, "Faults"): the stamps of its scans and
// odometry jump an hour ahead, then back. Nothing crashes, what the agent does in each phase is
// counted, and the temporary map it builds is still sent.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

TEST(AgentClockJumpTest, StampsJumpingAheadAndBackAreCountedAndTheAgentCarriesOn) {
  const sim::World world = testing::RoomWorld(testing::kPallet, 24.0);
  RecordingPublisher out;
  auto node = AgentNode::Create(testing::RoomOptions(world), &out, nullptr, world.static_map(), 0.0)
                  .value();
  constexpr double kHour = 3600.0;
  // 0-6 s: right; 6-12 s: an hour ahead; from 12 s: right again (an hour back).
  const auto clock = [](double t) { return t >= 6.0 && t < 12.0 ? t + kHour : t; };
  // Scans localized (not dropped) in each phase.
  std::vector<int64_t> localized_at = {0, 0, 0};
  testing::DriveNode(
      world, *node, 24.0,
      [&](double t) {
        localized_at[t < 6.0    ? 0
                     : t < 12.0 ? 1
                                : 2] =
            testing::Counter(*node, "scans") - testing::Counter(*node, "scans_out_of_order");
      },
      0.0, clock);
  node->Shutdown(24.0);
  const int64_t before = localized_at[0], ahead = localized_at[1] - localized_at[0],
                back = localized_at[2] - localized_at[1];
  std::printf(
      "clock jump: scans localized %lld before, %lld an hour ahead, %lld after jumping "
      "back; clock_steps_back %lld, scans_out_of_order %lld, odometry_out_of_order %lld, "
      "tempmaps_closed %lld, maps split %lld\n",
      (long long)before, (long long)ahead, (long long)back,
      (long long)testing::Counter(*node, "clock_steps_back"),
      (long long)testing::Counter(*node, "scans_out_of_order"),
      (long long)testing::Counter(*node, "odometry_out_of_order"),
      (long long)testing::Counter(*node, "tempmaps_closed"),
      (long long)node->pipeline().counters().temp_maps_split);
  EXPECT_GT(before, 100);
  EXPECT_GT(ahead, 100);  // ahead: time goes on, only faster once
  EXPECT_GT(back, 250) << "after the clock went back the agent must not wait for it to catch up";
  EXPECT_GE(testing::Counter(*node, "clock_steps_back"), 1);
  EXPECT_LE(testing::Counter(*node, "scans_out_of_order"), 1);
  EXPECT_GT(testing::Counter(*node, "tempmaps_closed"), 0);
  EXPECT_GT(out.Count("TEMPMAP_v1"), 0u);
  EXPECT_EQ(testing::Counter(*node, "malformed_messages"), 0);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
