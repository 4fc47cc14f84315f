#include "vehicle_agent/mapping/temp_map_builder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/map/map_io.h"
#include "sim/simulator.h"

namespace fleetmap::vehicle_agent {
namespace {

// The LivingLab hall with one pallet; the vehicle drives along the bottom aisle past it.
constexpr const char* kScenario = R"(
map: livinglab.yaml
duration_s: 16
seed: 5
objects:
  - {id: pallet, rect: {center: [12.0, 6.0], size: [1.2, 0.8]}}
vehicles:
  - {id: v1, route: [[6.0, 4.0], [20.0, 4.0]], speed_mps: 0.5}
)";

sim::World LivingLab() {
  const std::string dir = std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/";
  auto scenario = sim::ParseScenario(kScenario, dir + "builder_test.yaml").value();
  auto map = core::LoadMapServerMap(scenario.map_yaml).value();
  return sim::World::Create(scenario, std::move(map.grid)).value();
}

// Runs the builder over the whole scenario with the simulator's noisy odometry, anchored at
// the true start pose. Returns the closed map.
core::TempMap BuildAlongTheRoute(const sim::World& world, TempMapBuilderOptions options = {}) {
  sim::Simulator simulator(&world);
  TempMapBuilder builder(options);
  core::Pose2 last_odom;
  bool have_odom = false, started = false;
  core::Pose2 odom_at_last_scan;
  while (auto e = simulator.Next()) {
    if (auto* o = std::get_if<sim::OdometryEvent>(&*e)) {
      last_odom = o->odom_pose;
      have_odom = true;
    } else if (auto* s = std::get_if<sim::ScanEvent>(&*e)) {
      if (!have_odom) continue;
      if (!started) {
        builder.Start("v1", 1, s->scan.stamp_s, s->true_base_pose);
        started = true;
        odom_at_last_scan = last_odom;
      }
      builder.AddScan(s->scan, core::Between(odom_at_last_scan, last_odom),
                      world.scenario().vehicles[0].scanner_mount);
      odom_at_last_scan = last_odom;
    }
  }
  return builder.Close(simulator.now_s()).value();
}

TEST(TempMapBuilderTest, ThePalletIsInTheMapAtTheRightPlace) {
  const sim::World world = LivingLab();
  const core::TempMap map = BuildAlongTheRoute(world);
  EXPECT_TRUE(map.Validate().ok());
  // Placed by its (true) anchor, the pallet's near face (y = 5.6 m) must be occupied within
  // one cell, and the aisle in front of it free.
  const core::GridGeometry placed = map.PlacedGeometry();
  int occupied_near_face = 0, cells_checked = 0;
  for (double x = 11.6; x <= 12.4; x += 0.05) {
    ++cells_checked;
    bool hit = false;
    for (double dy : {-0.05, 0.0, 0.05}) {
      const core::CellIndex c = placed.WorldToCell({x, 5.625 + dy});
      hit |= placed.Contains(c) && map.grid.state(c) == core::CellState::kOccupied;
    }
    occupied_near_face += hit;
  }
  EXPECT_GE(occupied_near_face, cells_checked - 1);
  const core::CellIndex aisle = placed.WorldToCell({12.0, 4.8});
  EXPECT_EQ(map.grid.state(aisle), core::CellState::kFree);
  // The trajectory ends near the truth (14 m driven with noisy odometry).
  const core::Pose2 end_in_map = map.anchor_in_map * map.trajectory_in_temp.back().pose;
  const core::Pose2 truth = world.VehicleStateAt(0, map.trajectory_in_temp.back().stamp_s).pose;
  EXPECT_LT(std::hypot(end_in_map.x_m - truth.x_m, end_in_map.y_m - truth.y_m), 0.05);
  EXPECT_LT(std::abs(core::NormalizeAngle(end_in_map.theta_rad - truth.theta_rad)), 0.01);
}

TEST(TempMapBuilderTest, TheMapIsCroppedToWhatWasSeen) {
  const sim::World world = LivingLab();
  const core::TempMap map = BuildAlongTheRoute(world);
  // The hall is 18 m wide: a 20 m x 20 m area cropped to the observed cells is narrower.
  EXPECT_LT(map.grid.geometry().height() * map.grid.geometry().resolution_m(), 18.6);
  EXPECT_LT(map.grid.CountState(core::CellState::kUnknown), map.grid.geometry().num_cells() / 2);
}

TEST(TempMapBuilderTest, ClosesWhenTheVehicleNearsTheEdgeOrTheTimeIsUp) {
  TempMapBuilderOptions options;
  options.mapper.map.size_m = 12.0;
  options.edge_margin_m = 4.0;    // 2 m of travel from the centre is all it allows
  options.max_duration_s = 60.0;  // the edge closes it, not the time
  const sim::World world = LivingLab();
  sim::Simulator simulator(&world);
  TempMapBuilder builder(options);
  builder.Start("v1", 1, 0.0, world.VehicleStateAt(0, 0).pose);
  double closed_at = -1;
  core::Pose2 previous = world.VehicleStateAt(0, 0).pose;
  while (auto e = simulator.Next()) {
    auto* s = std::get_if<sim::ScanEvent>(&*e);
    if (!s) continue;
    const core::Pose2 delta = core::Between(previous, s->true_base_pose);
    previous = s->true_base_pose;
    if (builder.AddScan(s->scan, delta, {}).must_close) {
      closed_at = s->scan.stamp_s;
      break;
    }
  }
  EXPECT_NEAR(closed_at, 4.0, 0.2);  // 2 m at 0.5 m/s
  ASSERT_TRUE(builder.Close(closed_at).has_value());
  EXPECT_FALSE(builder.building());
  EXPECT_FALSE(builder.Close(closed_at).has_value());
}

// A map anchored a scan before its first scan: placed by its anchor and the odometry since,
// that scan must be where the vehicle truly was, not where it was at the anchor.
TEST(TempMapBuilderTest, AMapStartedBeforeItsFirstScanPlacesThatScanByTheOdometry) {
  const sim::World world = LivingLab();
  sim::Simulator simulator(&world);
  std::vector<sim::ScanEvent> scans;
  while (scans.size() < 2) {
    auto e = simulator.Next();
    ASSERT_TRUE(e.has_value());
    if (auto* s = std::get_if<sim::ScanEvent>(&*e)) scans.push_back(*s);
  }
  const core::Pose2 moved = core::Between(scans[0].true_base_pose, scans[1].true_base_pose);
  ASSERT_GT(std::hypot(moved.x_m, moved.y_m), 0.005);  // the vehicle drives between the scans

  TempMapBuilder split({});
  split.Start("v1", 2, scans[0].scan.stamp_s, scans[0].true_base_pose);
  const BuilderStep first = split.AddScan(scans[1].scan, moved, {});
  const core::Pose2 placed = scans[0].true_base_pose * first.pose_in_temp;
  EXPECT_NEAR(placed.x_m, scans[1].true_base_pose.x_m, 1e-9);
  EXPECT_NEAR(placed.y_m, scans[1].true_base_pose.y_m, 1e-9);
  EXPECT_NEAR(placed.theta_rad, scans[1].true_base_pose.theta_rad, 1e-9);
}

TEST(TempMapBuilderTest, CropKeepsGeometryConsistent) {
  core::OccupancyGrid grid(core::GridGeometry(0.1, 50, 40, core::Pose2(-2.5, -2.0, 0)));
  grid.SetState({10, 12}, core::CellState::kOccupied);
  grid.SetState({20, 15}, core::CellState::kFree);
  const core::OccupancyGrid cropped = CropToObserved(grid, 2);
  EXPECT_EQ(cropped.geometry().width(), 20 - 10 + 1 + 4);
  EXPECT_EQ(cropped.geometry().height(), 15 - 12 + 1 + 4);
  const Eigen::Vector2d world = grid.geometry().CellCenter({10, 12});
  EXPECT_EQ(cropped.state(cropped.geometry().WorldToCell(world)), core::CellState::kOccupied);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
