#include "sim/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/sim/sim_test_util.h"

namespace fleetmap::sim {
namespace {

constexpr const char* kRoom = R"(
map: room.yaml
duration_s: 30
seed: 4
objects:
  - {id: box, rect: {center: [7, 3], size: [1, 1]}, appear_s: 10}
actors:
  - {id: p, radius_m: 0.3, path: [[5, 5], [5, 4.5]], speed_mps: 0.1}
vehicles:
  - id: v1
    route: [[1, 3], [4, 3]]
    speed_mps: 0.5
)";

World RoomWorld() {
  return World::Create(ParseScenario(kRoom, "room_scenario.yaml").value(), testing::Room()).value();
}

TEST(SimulatorTest, EventsComeInTimeOrderAtTheConfiguredRates) {
  const World world = RoomWorld();
  Simulator sim(&world);
  double last = -1;
  int scans = 0, odoms = 0;
  while (auto e = sim.Next()) {
    ASSERT_GE(EventTime(*e), last);
    last = EventTime(*e);
    scans += std::holds_alternative<ScanEvent>(*e);
    odoms += std::holds_alternative<OdometryEvent>(*e);
  }
  EXPECT_NEAR(scans, 30 * 25, 1);  // S300 at 25 Hz
  EXPECT_NEAR(odoms, 30 * 50, 1);  // odometry at 50 Hz
}

TEST(SimulatorTest, SeesTheBoxOnlyAfterItAppears) {
  const World world = RoomWorld();
  Simulator sim(&world);
  // Beam straight ahead (index 270 of 541) from the vehicle: wall at 9.95 m before t = 10 s,
  // the box face at 6.5 m afterwards.
  while (auto e = sim.Next()) {
    const auto* scan = std::get_if<ScanEvent>(&*e);
    if (!scan) continue;
    const double x = scan->true_scanner_pose.x_m;
    const float r = scan->scan.ranges_m[270];
    if (!std::isfinite(r)) continue;  // a dropout
    if (scan->scan.stamp_s < 9.9) {
      ASSERT_NEAR(r, 9.95 - x, 0.15) << scan->scan.stamp_s;
    } else if (scan->scan.stamp_s > 10.1) {
      ASSERT_NEAR(r, 6.5 - x, 0.15) << scan->scan.stamp_s;
    }
  }
  const ObjectChangeSeen& seen = sim.observations().Seen(0, 0);
  EXPECT_GE(seen.appear_seen_s, 10.0);
  EXPECT_LT(seen.appear_seen_s, 10.1);
}

TEST(SimulatorTest, RangeNoiseHasTheModelsSpread) {
  const World world = RoomWorld();
  Simulator sim(&world);
  double sum = 0, sum2 = 0;
  int n = 0;
  while (auto e = sim.Next()) {
    const auto* scan = std::get_if<ScanEvent>(&*e);
    // Before the box appears, the forward beam sees the wall at a known true distance.
    if (!scan || scan->scan.stamp_s > 9.0) continue;
    const float r = scan->scan.ranges_m[270];
    if (!std::isfinite(r)) continue;
    const double err = r - (9.95 - scan->true_scanner_pose.x_m);
    sum += err, sum2 += err * err, ++n;
  }
  ASSERT_GT(n, 200);
  const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.01);
  EXPECT_NEAR(sigma, world.scenario().vehicles[0].scanner.range_sigma_m, 0.008);
}

TEST(SimulatorTest, OdometryDriftsButStaysClose) {
  const World world = RoomWorld();
  Simulator sim(&world);
  OdometryEvent last;
  while (auto e = sim.Next())
    if (auto* o = std::get_if<OdometryEvent>(&*e)) last = *o;
  // 3 m driven: odometry is noisy but within a few percent, and not identical to the truth.
  const core::Pose2 start = world.VehicleStateAt(0, 0).pose;
  const core::Pose2 true_inc = core::Between(start, last.true_base_pose);
  EXPECT_NEAR(last.odom_pose.x_m, true_inc.x_m, 0.2);
  EXPECT_NE(last.odom_pose.x_m, true_inc.x_m);
}

// The systematic part of the odometry error (a wheel's scale, a heading drift per metre)
// grows with the distance, unlike the per-increment noise, which averages out.
TEST(SimulatorTest, ASystematicOdometryErrorGrowsWithTheDistance) {
  std::string yaml = kRoom;
  yaml += R"(    odometry_noise: {rot_per_rot: 0, rot_per_trans_rad_m: 0, trans_per_trans: 0,
                     trans_per_rot_m_rad: 0, scale_sigma: 0.05, heading_drift_sigma_rad_m: 0.05}
)";
  const World world =
      World::Create(ParseScenario(yaml, "room_scenario.yaml").value(), testing::Room()).value();
  Simulator sim(&world);
  // Path lengths, increment by increment: the odometry's is the truth's times its scale.
  struct Reading {
    double true_m = 0, odom_m = 0, odom_turn_rad = 0;
  };
  Reading now, at_1m;
  core::Pose2 last_true = world.VehicleStateAt(0, 0).pose, last_odom;
  while (auto e = sim.Next()) {
    const auto* o = std::get_if<OdometryEvent>(&*e);
    if (!o) continue;
    now.true_m += (o->true_base_pose.translation() - last_true.translation()).norm();
    now.odom_m += (o->odom_pose.translation() - last_odom.translation()).norm();
    now.odom_turn_rad = o->odom_pose.theta_rad;
    last_true = o->true_base_pose, last_odom = o->odom_pose;
    if (at_1m.true_m == 0 && now.true_m > 1.0) at_1m = now;
  }
  ASSERT_GT(at_1m.true_m, 1.0);
  ASSERT_GT(now.true_m, 2.9);  // the 3 m leg, straight: the truth does not turn
  const double scale = at_1m.odom_m / at_1m.true_m;
  EXPECT_GT(std::abs(scale - 1), 1e-3);
  EXPECT_GT(std::abs(at_1m.odom_turn_rad), 1e-3);
  EXPECT_NEAR(now.odom_m / now.true_m, scale, 1e-9);
  EXPECT_NEAR(now.odom_turn_rad / now.true_m, at_1m.odom_turn_rad / at_1m.true_m, 1e-9);
}

TEST(SimulatorTest, SameSeedSameScans) {
  const World world = RoomWorld();
  Simulator a(&world), b(&world);
  for (int i = 0; i < 200; ++i) {
    auto ea = a.Next(), eb = b.Next();
    ASSERT_TRUE(ea && eb);
    if (auto* sa = std::get_if<ScanEvent>(&*ea)) {
      ASSERT_EQ(sa->scan.ranges_m, std::get<ScanEvent>(*eb).scan.ranges_m);
    }
  }
}

}  // namespace
}  // namespace fleetmap::sim
