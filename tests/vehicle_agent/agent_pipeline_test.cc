#include "vehicle_agent/agent_pipeline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/map/map_io.h"
#include "sim/simulator.h"

namespace fleetmap::vehicle_agent {
namespace {

// One vehicle along the bottom aisle; a pallet appears in its view at 8 s.
constexpr const char* kScenario = R"(
map: livinglab.yaml
duration_s: 40
seed: 11
objects:
  - {id: pallet, rect: {center: [16.0, 5.6], size: [1.2, 0.8]}, appear_s: 8}
vehicles:
  - {id: v1, route: [[6.0, 4.0], [24.0, 4.0]], speed_mps: 0.5, scanner_mount: [0.3, 0.0, 0.0]}
)";

// The same drive with the pallet there from the start, beside the vehicle, left behind.
constexpr const char* kPalletFromTheStart = R"(
map: livinglab.yaml
duration_s: 30
seed: 11
objects:
  - {id: pallet, rect: {center: [6.0, 5.6], size: [1.2, 0.8]}}
vehicles:
  - {id: v1, route: [[6.0, 4.0], [24.0, 4.0]], speed_mps: 0.5, scanner_mount: [0.3, 0.0, 0.0]}
)";

struct DriveResult {
  std::vector<core::TempMap> maps;
  std::vector<AgentStep> steps;
  std::vector<core::Pose2> truth;
  double pallet_seen_s = NAN;
  AgentCounters counters;
};

// `skip_scan(t)`: scans the agent does not get to (it fell behind); odometry all arrives.
DriveResult Drive(
    const std::function<bool(double)>& skip_scan = [](double) { return false; },
    const std::function<void(AgentPipelineOptions&)>& configure = [](AgentPipelineOptions&) {},
    const char* scenario_text = kScenario,
    const std::function<void(double t_s, AgentPipeline&)>& before_scan = {}) {
  const std::string dir = std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/";
  const auto scenario = sim::ParseScenario(scenario_text, dir + "pipeline_test.yaml").value();
  auto map = core::LoadMapServerMap(scenario.map_yaml).value();
  const sim::World world = sim::World::Create(scenario, map.grid).value();
  AgentPipelineOptions options;
  options.vehicle_id = "v1";
  options.scanner_in_base = scenario.vehicles[0].scanner_mount;
  options.localizer.initial_pose_in_map = world.VehicleStateAt(0, 0).pose;
  options.localizer.initial_sigma_xy_m = 0.05;
  options.localizer.initial_sigma_theta_rad = 0.02;
  options.divergence.map_at_start = false;  // what d(t) opens (see TheVehicleMapsWhat...)
  configure(options);
  AgentPipeline pipeline(options);
  EXPECT_TRUE(pipeline.SetMap(map.grid, 1).ok());
  sim::Simulator simulator(&world);
  DriveResult run;
  while (auto e = simulator.Next()) {
    if (auto* o = std::get_if<sim::OdometryEvent>(&*e)) {
      pipeline.AddOdometry({o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps});
    } else if (auto* s = std::get_if<sim::ScanEvent>(&*e); s && !skip_scan(s->scan.stamp_s)) {
      if (before_scan) before_scan(s->scan.stamp_s, pipeline);
      AgentStep step = pipeline.AddScan(s->scan);
      if (step.closed_map) run.maps.push_back(*step.closed_map);
      run.truth.push_back(s->true_base_pose);
      run.steps.push_back(std::move(step));
    }
  }
  if (auto last = pipeline.Flush(simulator.now_s())) run.maps.push_back(*last);
  run.pallet_seen_s = simulator.observations().Seen(0, 0).appear_seen_s;
  run.counters = pipeline.counters();
  return run;
}

TEST(AgentPipelineTest, DetectsThePalletAndMapsItWhereItIs) {
  const DriveResult run = Drive();
  // Localization tracks the truth.
  std::vector<double> errors;
  for (size_t i = 0; i < run.steps.size(); ++i) {
    const core::Pose2& p = run.steps[i].pose.pose_in_map;
    errors.push_back(std::hypot(p.x_m - run.truth[i].x_m, p.y_m - run.truth[i].y_m));
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.05);
  // d(t) rose soon after the pallet came into view, and a temporary map was built.
  ASSERT_FALSE(std::isnan(run.pallet_seen_s));
  double started_s = NAN;
  for (const AgentStep& s : run.steps) {
    if (s.divergence.started && s.divergence.stamp_s >= run.pallet_seen_s) {
      started_s = s.divergence.stamp_s;
      break;
    }
  }
  ASSERT_FALSE(std::isnan(started_s));
  EXPECT_LT(started_s - run.pallet_seen_s, 1.0);
  ASSERT_FALSE(run.maps.empty());
  // The pallet's near face (y = 5.2 m) is in the map that covers it, within one cell, when
  // the map is placed by its anchor (the localized pose where it started).
  int seen = 0, cells = 0;
  for (double x = 15.5; x <= 16.5; x += 0.05) {
    ++cells;
    bool hit = false;
    for (const core::TempMap& m : run.maps) {
      const core::GridGeometry placed = m.PlacedGeometry();
      for (double dy : {-0.05, 0.0, 0.05}) {
        const core::CellIndex c = placed.WorldToCell({x, 5.225 + dy});
        hit |= placed.Contains(c) && m.grid.state(c) == core::CellState::kOccupied;
      }
    }
    seen += hit;
  }
  EXPECT_GE(seen, cells - 2);
}

// Each map carries how sure localization was of its anchor: the covariance of the pose of the
// scan the map started at, which the aggregator weighs corrections against.
TEST(AgentPipelineTest, EachMapCarriesTheCovarianceOfItsAnchor) {
  const DriveResult run = Drive();
  ASSERT_FALSE(run.maps.empty());
  for (const core::TempMap& m : run.maps) {
    ASSERT_TRUE(m.anchor_covariance.has_value()) << "map " << m.sequence;
    const AgentStep* start = nullptr;
    for (const AgentStep& s : run.steps)
      if (s.pose.stamp_s == m.start_s) start = &s;
    ASSERT_NE(start, nullptr) << "map " << m.sequence;
    EXPECT_EQ(m.anchor_in_map.x_m, start->pose.pose_in_map.x_m);
    EXPECT_EQ(*m.anchor_covariance, start->pose.covariance);
    EXPECT_GT((*m.anchor_covariance)(0, 0), 0.0);  // a particle set, never certain
  }
}

// A pallet in view from the first scan is part of the past d(t) compares with: d never
// rises, and only the map every vehicle builds when it starts holds the pallet.
TEST(AgentPipelineTest, TheVehicleMapsWhatIsInViewWhenItStarts) {
  for (const bool at_start : {false, true}) {
    const DriveResult run =
        Drive([](double) { return false; },
              [&](AgentPipelineOptions& o) { o.divergence.map_at_start = at_start; },
              kPalletFromTheStart);
    ASSERT_FALSE(run.steps.empty());
    EXPECT_EQ(run.steps.front().divergence.started, at_start);
    int pallet_cells = 0;  // the near face, y = 5.2 m
    for (const core::TempMap& m : run.maps) {
      const core::GridGeometry placed = m.PlacedGeometry();
      for (double x = 5.5; x <= 6.5; x += 0.05) {
        const core::CellIndex c = placed.WorldToCell({x, 5.225});
        pallet_cells += placed.Contains(c) && m.grid.state(c) == core::CellState::kOccupied;
      }
    }
    if (at_start) {
      EXPECT_GE(pallet_cells, 10);
    } else {
      EXPECT_EQ(pallet_cells, 0) << run.maps.size() << " maps";
    }
  }
}

TEST(AgentPipelineTest, ScansSkippedForSecondsLoseNoMotion) {
  // 4 s without a scan at 0.5 m/s: 2 m between two processed scans, twice max_odometry_step_m.
  // Composed sample by sample it is motion, not a jump, and localization carries on.
  // Without the tracker's allowance for gaps, so that only composing every sample can pass.
  const DriveResult run = Drive([](double t_s) { return t_s > 10.0 && t_s < 14.0; },
                                [](AgentPipelineOptions& o) {
                                  o.localizer.max_odometry_speed_mps = 0.0;
                                  o.localizer.max_odometry_yaw_rate_radps = 0.0;
                                });
  ASSERT_FALSE(run.steps.empty());
  EXPECT_EQ(run.steps.back().localization.counters.odometry_jumps, 0);
  std::vector<double> errors;
  for (size_t i = 0; i < run.steps.size(); ++i) {
    if (run.steps[i].pose.stamp_s < 14.0) continue;
    const core::Pose2& p = run.steps[i].pose.pose_in_map;
    errors.push_back(std::hypot(p.x_m - run.truth[i].x_m, p.y_m - run.truth[i].y_m));
  }
  ASSERT_GT(errors.size(), 100u);
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.05);
  EXPECT_LT(errors.back(), 0.3);
}

TEST(AgentPipelineTest, AMapBeingBuiltClosesAtAScanGapAndTheChangeGoesOnInANewOne) {
  // The pallet is in view from 8 s; no scan between 9.5 and 11 s (odometry goes on).
  const auto gap = [](double t_s) { return t_s >= 9.5 && t_s < 11.0; };
  const DriveResult run = Drive(gap);
  const DriveResult whole = Drive();
  bool closed_at_gap = false, started_after_gap = false;
  for (const core::TempMap& m : run.maps) {
    ASSERT_FALSE(m.trajectory_in_temp.empty());
    for (size_t i = 1; i < m.trajectory_in_temp.size(); ++i) {
      EXPECT_LE(m.trajectory_in_temp[i].stamp_s - m.trajectory_in_temp[i - 1].stamp_s, 1.0)
          << "map " << m.sequence << " bridges a gap";
    }
    closed_at_gap |= m.trajectory_in_temp.back().stamp_s < 9.5 && m.end_s < 9.5 &&
                     m.trajectory_in_temp.back().stamp_s > 9.0;
    started_after_gap |= m.start_s >= 11.0 && m.start_s < 11.2;
  }
  EXPECT_TRUE(closed_at_gap) << "the map being built did not close at its last scan";
  EXPECT_TRUE(started_after_gap) << "no new map at the first scan after the gap";
  // Without the gap, one map spans 9.5-11 s: the split is the gap's doing.
  bool spans = false;
  for (const core::TempMap& m : whole.maps) spans |= m.start_s < 9.5 && m.end_s >= 11.0;
  EXPECT_TRUE(spans);
}

// Every temporary map is anchored at the localized pose of its own first scan, which is its
// frame T; a map split from the one before (its time up, here every second) too, not at the
// scan that closed the last one, a scan's motion behind.
TEST(AgentPipelineTest, EveryMapIsAnchoredAtItsFirstScan) {
  const DriveResult run = Drive([](double) { return false; },
                                [](AgentPipelineOptions& o) { o.builder.max_duration_s = 1.0; });
  EXPECT_GE(run.counters.temp_maps_split, 3);
  for (const core::TempMap& m : run.maps) {
    ASSERT_FALSE(m.trajectory_in_temp.empty());
    const core::TimedPose& first = m.trajectory_in_temp.front();
    EXPECT_EQ(first.stamp_s, m.start_s) << "map " << m.sequence;
    const auto step = std::find_if(run.steps.begin(), run.steps.end(), [&](const AgentStep& s) {
      return s.pose.stamp_s == first.stamp_s;
    });
    ASSERT_NE(step, run.steps.end());
    const core::Pose2& localized = step->pose.pose_in_map;
    const core::Pose2 placed = m.anchor_in_map * first.pose;
    EXPECT_NEAR(placed.x_m, localized.x_m, 1e-9) << "map " << m.sequence;
    EXPECT_NEAR(placed.y_m, localized.y_m, 1e-9) << "map " << m.sequence;
    EXPECT_NEAR(core::NormalizeAngle(placed.theta_rad - localized.theta_rad), 0.0, 1e-9);
  }
}

// The vehicle's pose jumps 4.5 m across the aisle and turns while it maps the pallet (a
// kidnapping): the scans stop making sense, it finds itself by a search, and the map it was
// building then, anchored at the wrong pose, is dropped, not sent.
TEST(AgentPipelineTest, AMapBeingBuiltWhenTheVehicleFindsItselfElsewhereIsDropped) {
  bool carried_off = false;
  const auto carry_off = [&](double t_s, AgentPipeline& pipeline) {
    if (carried_off || t_s < 10.0) return;
    carried_off = true;
    const Eigen::Matrix3d sure = Eigen::Vector3d(0.0025, 0.0025, 0.0004).asDiagonal();
    ASSERT_TRUE(pipeline.InitializeAt(core::Pose2(11.0, 8.5, 0.6), sure).ok());
  };
  const DriveResult run =
      Drive([](double) { return false; }, [](AgentPipelineOptions&) {}, kScenario, carry_off);
  double relocalized_s = NAN;
  bool building_then = false;
  for (size_t i = 0; i < run.steps.size(); ++i) {
    if (!run.steps[i].localization.relocalized || !std::isnan(relocalized_s)) continue;
    relocalized_s = run.steps[i].pose.stamp_s;
    building_then = i > 0 && run.steps[i - 1].building;
  }
  ASSERT_FALSE(std::isnan(relocalized_s)) << "never found itself";
  EXPECT_LT(relocalized_s, 15.0);
  EXPECT_TRUE(building_then);
  EXPECT_EQ(run.counters.temp_maps_dropped, 1);
  // Every map sent starts where the vehicle truly was: the one begun from the wrong pose
  // (d(t) rose with the pose wrong) is the one dropped.
  for (const core::TempMap& m : run.maps) {
    size_t k = 0;
    while (k + 1 < run.steps.size() && run.steps[k].pose.stamp_s < m.start_s) ++k;
    const core::Pose2 off = core::Between(run.truth[k], m.anchor_in_map);
    EXPECT_LT(std::hypot(off.x_m, off.y_m), 0.2) << "map " << m.sequence << " from " << m.start_s;
  }
  // Back on the truth by the end.
  const core::Pose2 d = core::Between(run.truth.back(), run.steps.back().pose.pose_in_map);
  EXPECT_LT(std::hypot(d.x_m, d.y_m), 0.1);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
