#include "vehicle_agent/localization/localizer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/vehicle_agent/agent_sim_util.h"

namespace fleetmap::vehicle_agent {
namespace {

using sim_testing::Errors;
using sim_testing::HeadingErrorRad;
using sim_testing::Max;
using sim_testing::Median;
using sim_testing::RunOptions;
using sim_testing::RunVehicle;
using sim_testing::ScanRecord;
using sim_testing::SimRun;
using sim_testing::TranslationError;

constexpr double kDeg = M_PI / 180.0;

// The paper's route (addition scenario: unmapped pallets and parked robots, noisy odometry
// from the simulator), started 0.5 m and 10 deg off.
TEST(LocalizerTest, ConvergesFromHalfAMetreAndTracksTheLivingLabRoute) {
  const sim::World world = sim_testing::LoadWorld("addition.yaml");
  RunOptions options;
  options.initial_offset = core::Pose2(0.4, -0.3, 10 * kDeg);  // 0.5 m, 10 deg
  const SimRun run = RunVehicle(world, options);
  ASSERT_GT(run.scans.size(), 7000u);
  EXPECT_LT(TranslationError(run.scans[125]), 0.10) << "not converged after 5 s";
  const auto error_m = Errors(run, 10.0, 1e9, TranslationError);
  const auto error_rad = Errors(run, 10.0, 1e9, HeadingErrorRad);
  EXPECT_LT(Median(error_m), 0.05);
  EXPECT_LT(Median(error_rad), 1.0 * kDeg);
  EXPECT_LT(Max(error_m), 0.20);
  EXPECT_LT(Max(error_rad), 3.0 * kDeg);
  // Converged: KLD sampling came down from the 3000 initial particles to the minimum.
  EXPECT_EQ(run.scans.back().stats.particles, LocalizerOptions().kld.min_particles);
  for (const auto& r : run.scans) ASSERT_TRUE(r.estimate.Validate().ok()) << r.stamp_s;
}

// Wheels 6 % too large: the odometry reports every distance 6 % short of the truth... or here,
// long. The filter learns the scale from where the laser fixes the position, and tracks with
// it; the same drive with the scale switched off trusts the odometry's distances.
TEST(LocalizerTest, LearnsTheOdometrysScaleAndTracksWithIt) {
  const sim::World world = sim_testing::LoadWorld("addition.yaml");
  const auto run_with = [&](bool learn) {
    RunOptions options;
    options.end_s = 120.0;
    if (!learn) {
      options.localizer.odometry_scale.initial_sigma = 0.0;
      options.localizer.odometry_scale.walk_sigma_per_sqrt_m = 0.0;
    }
    double learnt = 1.0;
    options.before_scan = [&](double, Localizer& l) { learnt = l.odometry_scale(); };
    options.corrupt = [](core::OdometrySample& odom, core::LaserScan&) {
      odom.pose_in_odom.x_m *= 1.06;  // every increment's length, whatever its heading
      odom.pose_in_odom.y_m *= 1.06;
      odom.v_mps *= 1.06;
    };
    const SimRun run = RunVehicle(world, options);
    return std::make_pair(run, learnt);
  };
  const auto [learning, scale] = run_with(true);
  EXPECT_NEAR(scale, 1.0 / 1.06, 0.02);
  const auto [trusting, unchanged] = run_with(false);
  EXPECT_EQ(unchanged, 1.0);
  const auto learnt_error = Errors(learning, 20.0, 1e9, TranslationError);
  const auto trusted_error = Errors(trusting, 20.0, 1e9, TranslationError);
  EXPECT_LT(Median(learnt_error), 0.05);
  EXPECT_LE(Median(learnt_error), Median(trusted_error));
}

TEST(LocalizerTest, TheSameSeedGivesTheSamePoses) {
  const sim::World world = sim_testing::LoadWorld("addition.yaml");
  RunOptions options;
  options.end_s = 8.0;
  options.initial_offset = core::Pose2(0.3, 0.2, 5 * kDeg);
  const SimRun a = RunVehicle(world, options), b = RunVehicle(world, options);
  options.localizer.seed = 2;
  const SimRun c = RunVehicle(world, options);
  ASSERT_EQ(a.scans.size(), b.scans.size());
  bool differs = false;
  for (size_t i = 0; i < a.scans.size(); ++i) {
    ASSERT_EQ(a.scans[i].estimate.pose_in_map.x_m, b.scans[i].estimate.pose_in_map.x_m);
    ASSERT_EQ(a.scans[i].estimate.pose_in_map.theta_rad, b.scans[i].estimate.pose_in_map.theta_rad);
    differs |= a.scans[i].estimate.pose_in_map.x_m != c.scans[i].estimate.pose_in_map.x_m;
  }
  EXPECT_TRUE(differs) << "the seed has no effect";
}

// A pallet appears in the aisle at 30 s; at 45 s the current map with the pallet arrives as
// version 2. The filter keeps its particles and keeps tracking on the new map.
constexpr const char* kPalletScenario = R"(
map: livinglab.yaml
duration_s: 75
seed: 5
objects:
  - {id: p, rect: {center: [28.0, 5.0], size: [1.2, 0.8]}, appear_s: 30}
vehicles:
  - id: v
    scanner_mount: [0.3, 0.0, 0.0]
    route: [[5.0, 4.0], [55.0, 4.0]]
)";

TEST(LocalizerTest, SwapsToANewMapVersionWithoutLosingTheParticles) {
  const sim::World world = sim_testing::MakeWorld(kPalletScenario);
  const core::OccupancyGrid with_pallet = world.TrueMapAt(40.0);
  RunOptions options;
  size_t particles_before = 0;
  core::Pose2 mean_before;
  options.before_scan = [&](double t_s, Localizer& localizer) {
    if (t_s < 45.0 || localizer.map_version() == 2) return;
    particles_before = localizer.particles().size();
    mean_before = ComputeMoments(localizer.particles()).mean;
    ASSERT_TRUE(localizer.SetMap(with_pallet, 2).ok());
    EXPECT_EQ(localizer.particles().size(), particles_before);
    EXPECT_EQ(ComputeMoments(localizer.particles()).mean.x_m, mean_before.x_m);
  };
  const SimRun run = RunVehicle(world, options);
  ASSERT_GT(particles_before, 0u) << "the swap never happened";
  EXPECT_EQ(run.scans.back().estimate.map_version, 2);
  EXPECT_EQ(run.scans.front().estimate.map_version, 1);
  const auto after = Errors(run, 45.0, 1e9, TranslationError);
  EXPECT_LT(Median(after), 0.05);
  EXPECT_LT(Max(after), 0.15);
  EXPECT_LT(Median(Errors(run, 45.0, 1e9, HeadingErrorRad)), 1.0 * kDeg);
}

// A new version taken in around its change (UpdateMap, the pallet's cells) tracks and scores
// every later scan exactly as the whole map taken in afresh (SetMap).
TEST(LocalizerTest, AVersionUpdatedAroundItsChangeGivesWhatTheWholeMapGives) {
  const sim::World world = sim_testing::MakeWorld(kPalletScenario);
  const core::OccupancyGrid with_pallet = world.TrueMapAt(40.0);
  const core::GridGeometry& g = with_pallet.geometry();
  const core::CellIndex a = g.WorldToCell({27.3, 4.5}), b = g.WorldToCell({28.7, 5.5});
  const core::CellWindow pallet{a.x, a.y, b.x - a.x + 1, b.y - a.y + 1};
  SimRun runs[2];
  for (bool update : {false, true}) {
    RunOptions options;
    options.end_s = 60.0;
    options.before_scan = [&](double t_s, Localizer& localizer) {
      if (t_s < 45.0 || localizer.map_version() == 2) return;
      ASSERT_TRUE(
          (update ? localizer.UpdateMap(with_pallet, 2, pallet) : localizer.SetMap(with_pallet, 2))
              .ok());
    };
    runs[update] = RunVehicle(world, options);
  }
  ASSERT_EQ(runs[0].scans.size(), runs[1].scans.size());
  ASSERT_EQ(runs[1].scans.back().estimate.map_version, 2);
  for (size_t i = 0; i < runs[0].scans.size(); ++i) {
    const ScanRecord &whole = runs[0].scans[i], &updated = runs[1].scans[i];
    ASSERT_EQ(whole.estimate.pose_in_map.x_m, updated.estimate.pose_in_map.x_m) << whole.stamp_s;
    ASSERT_EQ(whole.estimate.pose_in_map.theta_rad, updated.estimate.pose_in_map.theta_rad);
    ASSERT_TRUE(whole.stats.w_avg == updated.stats.w_avg ||
                (std::isnan(whole.stats.w_avg) && std::isnan(updated.stats.w_avg)))
        << whole.stamp_s;
  }
}

// A vehicle that localizes itself reports noisy poses (3 cm, 0.6 deg) at 10 Hz.
constexpr const char* kExternalScenario = R"(
map: livinglab.yaml
duration_s: 40
seed: 6
vehicles:
  - id: v
    scanner_mount: [0.3, 0.0, 0.0]
    route: [[5.0, 4.0], [55.0, 4.0]]
    external_pose: {sigma_xy_m: 0.03, sigma_theta_rad: 0.01, rate_hz: 10}
)";

TEST(LocalizerTest, PassesAnExternalPoseThroughAndFallsBackToMclWhenItStops) {
  const sim::World world = sim_testing::MakeWorld(kExternalScenario);
  RunOptions options;
  options.localizer.external_pose_mode = ExternalPoseMode::kPassThrough;
  options.initial_offset = core::Pose2(2.0, 1.0, 0.0);  // MCL alone would be lost
  options.external_poses_until_s = 20.0;
  const SimRun run = RunVehicle(world, options);
  int external = 0;
  for (const auto& r : run.scans) {
    if (r.stamp_s > 1.0 && r.stamp_s < 20.0) {
      ASSERT_TRUE(r.stats.external) << r.stamp_s;
      ++external;
    }
    if (r.stamp_s > 21.5) {
      ASSERT_FALSE(r.stats.external) << r.stamp_s;
    }
  }
  EXPECT_GT(external, 400);
  EXPECT_LT(Median(Errors(run, 1.0, 20.0, TranslationError)), 0.06);
  EXPECT_EQ(run.counters.external_reinits, 1);  // MCL restarted from the last external pose
  EXPECT_LT(Median(Errors(run, 25.0, 1e9, TranslationError)), 0.05);
}

TEST(LocalizerTest, FusingExternalPosesRecoversAFilterThatStartedFarOff) {
  const sim::World world = sim_testing::MakeWorld(kExternalScenario);
  RunOptions options;
  options.initial_offset = core::Pose2(3.0, 1.5, 20 * kDeg);  // beyond MCL's reach
  options.external_poses_until_s = 1e9;
  options.localizer.external_pose_mode = ExternalPoseMode::kIgnore;
  options.localizer.lost_after_s = 0.0;  // MCL alone: never searches the map
  const SimRun ignored = RunVehicle(world, options);
  EXPECT_GT(Median(Errors(ignored, 20.0, 1e9, TranslationError)), 0.5) << "MCL found it alone";
  options.localizer.external_pose_mode = ExternalPoseMode::kFuse;
  const SimRun fused = RunVehicle(world, options);
  EXPECT_GE(fused.counters.external_reinits, 1);
  EXPECT_LT(Median(Errors(fused, 5.0, 1e9, TranslationError)), 0.05);
  EXPECT_LT(Median(Errors(fused, 5.0, 1e9, HeadingErrorRad)), 1.0 * kDeg);
}

// A 6 m x 4 m room with a box in one corner: small enough for global localization with the
// default particle budget, and not symmetric.
constexpr const char* kRoomScenario = R"(
map: room.yaml
duration_s: 30
seed: 7
vehicles:
  - id: v
    route: [[1.5, 1.0], [4.5, 1.0], [4.5, 3.0], [1.5, 3.0]]
    loop: true
)";

core::OccupancyGrid RoomWithBox() {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 120, 80));
  for (int y = 0; y < 80; ++y) {
    for (int x = 0; x < 120; ++x) {
      const bool wall = x == 0 || y == 0 || x == 119 || y == 79;
      const bool box = x >= 100 && y >= 60;
      grid.SetState({x, y}, wall || box ? core::CellState::kOccupied : core::CellState::kFree);
    }
  }
  return grid;
}

TEST(LocalizerTest, GlobalInitialisationFindsThePoseInASmallRoom) {
  auto scenario = sim::ParseScenario(kRoomScenario, "room_scenario.yaml");
  ASSERT_TRUE(scenario.ok()) << scenario.status().ToString();
  auto world = sim::World::Create(std::move(scenario).value(), RoomWithBox());
  ASSERT_TRUE(world.ok()) << world.status().ToString();
  RunOptions options;
  options.localizer.initial_pose_mode = InitialPoseMode::kGlobal;
  options.localizer.kld.max_particles = 5000;
  double spread_m2 = 0.0;
  options.before_scan = [&](double, Localizer& localizer) {
    if (spread_m2 == 0.0) spread_m2 = ComputeMoments(localizer.particles()).covariance(0, 0);
  };
  const SimRun run = RunVehicle(*world, options);
  EXPECT_GT(spread_m2, 1.0) << "the particles did not start all over the room";
  EXPECT_LT(Median(Errors(run, 15.0, 1e9, TranslationError)), 0.05);
  EXPECT_LT(Median(Errors(run, 15.0, 1e9, HeadingErrorRad)), 1.0 * kDeg);
}

// An agent that stalls (seen: 6.7 s on a slow disk) skips the scans of that time but gets every
// odometry sample. Predicted as one increment, 6.7 m of motion spread the particles over metres
// and this vehicle came out of the gap 2.9 m off and stayed 2-3 m off; predicted along the
// odometry's path, the first pose after the gap is within decimetres and tracking goes on.
// Over gaps starting every 2.5 s from 5 to 80 s, for the first two of fleet_short.yaml's
// vehicles: before, the first pose after the gap was more than 0.3 m off in 15 of 60 (one
// stayed off); now at most 0.17 m, and within 0.09 m from 5 s after the gap on.
TEST(LocalizerTest, TracksOnAfterSecondsWithoutScansWithOdometryAllAlong) {
  const sim::World world = sim_testing::LoadWorld("fleet_short.yaml");
  RunOptions options;
  options.vehicle = 1;
  options.end_s = 70.0;
  options.gap_from_s = 27.5;
  options.gap_to_s = 34.2;
  const SimRun run = RunVehicle(world, options);
  ASSERT_FALSE(Errors(run, 34.2, 34.3, TranslationError).empty());
  EXPECT_LT(Errors(run, 34.2, 34.3, TranslationError).front(), 0.2)
      << "the first pose after the gap";
  const auto after = Errors(run, 39.2, 1e9, TranslationError);
  ASSERT_GT(after.size(), 500u);
  EXPECT_LT(Median(after), 0.05);
  EXPECT_LT(Max(after), 0.10);
  EXPECT_EQ(run.counters.odometry_jumps, 0);
  for (const auto& r : run.scans) ASSERT_TRUE(r.stamp_s < 27.5 || r.stamp_s >= 34.2) << r.stamp_s;
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
