#include "sim/worldgen/scenario_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/map/map_io.h"
#include "sim/world.h"
#include "sim/worldgen/free_space.h"
#include "sim/worldgen/world_generator.h"
#include "tests/support/data_dir.h"

namespace fleetmap::sim::worldgen {
namespace {

using ::testing::HasSubstr;

core::OccupancyGrid Warehouse(uint64_t seed) {
  WorldOptions o;
  o.style = BuildingStyle::kRackedWarehouse;
  o.seed = seed;
  o.length_m = 45;
  o.width_m = 30;
  o.render.rotation_rad = 0.3;
  return GenerateWorld(o).value().map.grid;
}

// Every point of every leg of every vehicle's loop.
template <typename Fn>
void ForEachRoutePoint(const sim::Scenario& s, Fn fn) {
  for (const sim::VehicleSpec& v : s.vehicles)
    for (size_t i = 0; i < v.route_m.size(); ++i) {
      const Eigen::Vector2d a = v.route_m[i], b = v.route_m[(i + 1) % v.route_m.size()];
      for (int k = 0; k <= 100; ++k) fn(a + (b - a) * (k / 100.0));
    }
}

TEST(ScenarioWriterTest, RoutesKeepTheirClearanceAndEveryChangeIsPassedAfterwards) {
  const core::OccupancyGrid map = Warehouse(4);
  ScenarioOptions o;
  o.seed = 9;
  auto written = WriteScenarioFor(map, "warehouse.yaml", o);
  ASSERT_TRUE(written.ok()) << written.status().ToString();
  EXPECT_EQ(written->fitted, "");
  const sim::Scenario* s = &written->scenario;
  ASSERT_EQ(s->vehicles.size(), 3u);
  EXPECT_EQ(s->vehicles[1].scanner.name, "microScan3");
  // Routes keep (nearly: the planning grid is 0.1 m) their 0.6 m from walls and unknown space.
  auto clear = FreeSpace::Of(map, o.vehicle_clearance_m - 0.1);
  ASSERT_TRUE(clear.ok());
  int points = 0;
  ForEachRoutePoint(*s, [&](const Eigen::Vector2d& p) {
    ++points;
    EXPECT_TRUE(clear->Contains(p)) << p.transpose();
  });
  EXPECT_GT(points, 0);

  auto world = sim::World::Create(*s, map);
  ASSERT_TRUE(world.ok()) << world.status().ToString();
  ASSERT_EQ(s->objects.size(), 5u);
  for (const sim::SemiStaticObject& obj : s->objects) {
    SCOPED_TRACE(obj.id);
    const double changed = std::isfinite(obj.disappear_s) ? obj.disappear_s : obj.appear_s;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& p : obj.polygon_m) centre += p / obj.polygon_m.size();
    // Some vehicle drives by (within 5 m) after the change.
    bool seen_after = false;
    for (size_t v = 0; v < s->vehicles.size() && !seen_after; ++v)
      for (double t = changed + 1; t < s->duration_s && !seen_after; t += 0.5)
        seen_after = (world->VehicleStateAt(v, t).pose.translation() - centre).norm() < 5.0;
    EXPECT_TRUE(seen_after);
  }
  ASSERT_EQ(s->actors.size(), 3u);
  EXPECT_EQ(s->actors[2].kind, "forklift");     // a warehouse has room for one
  EXPECT_GT(s->actors[2].motion.dwell_s, 0.0);  // it stops
  EXPECT_GT(s->actors[1].motion.dwell_s, 0.0);  // a person who stands a while
}

// The longest time, seconds, in which an actor's position stays within 1 mm.
double LongestStandStill(const sim::World& world, size_t actor, double duration_s) {
  constexpr double kStep_s = 0.05;
  double longest = 0.0, since = 0.0;
  Eigen::Vector2d last = world.ActorPositionAt(actor, 0.0);
  for (double t = kStep_s; t <= duration_s; t += kStep_s) {
    const Eigen::Vector2d p = world.ActorPositionAt(actor, t);
    if ((p - last).norm() > 1e-3) since = t;
    longest = std::max(longest, t - since);
    last = p;
  }
  return longest;
}

// People and forklifts are under way when the scenario starts: none waits at its first point
// (a forklift that stood there for half a minute would be a parked vehicle, which belongs in
// the map), and none stands longer than its dwell plus a turn at the end of its path. The
// start in the past survives writing and reading the scenario.
TEST(ScenarioWriterTest, ActorsAreUnderWayFromTheStartAndStandOnlyForTheirDwell) {
  const core::OccupancyGrid map = Warehouse(4);
  for (uint64_t seed : {9, 10, 11}) {
    ScenarioOptions o;
    o.seed = seed;
    auto written = WriteScenarioFor(map, "warehouse.yaml", o);
    ASSERT_TRUE(written.ok()) << written.status().ToString();
    auto reread = sim::ParseScenario(sim::ScenarioToYaml(written->scenario, "warehouse.yaml"), "w");
    ASSERT_TRUE(reread.ok()) << reread.status().ToString();
    auto world = sim::World::Create(*reread, map);
    ASSERT_TRUE(world.ok()) << world.status().ToString();
    ASSERT_EQ(reread->actors.size(), written->scenario.actors.size());
    for (size_t a = 0; a < reread->actors.size(); ++a) {
      const sim::DynamicActor& actor = reread->actors[a];
      SCOPED_TRACE(actor.id + " of seed " + std::to_string(seed));
      EXPECT_LE(actor.motion.start_s, 0.0);
      EXPECT_NEAR(actor.motion.start_s, written->scenario.actors[a].motion.start_s, 1e-3);
      const double turn_s = M_PI / actor.motion.angular_speed_radps;
      EXPECT_LE(LongestStandStill(*world, a, reread->duration_s),
                actor.motion.dwell_s + turn_s + 0.2);
    }
  }
}

TEST(ScenarioWriterTest, TheSameSeedWritesTheSameScenario) {
  const core::OccupancyGrid map = Warehouse(2);
  ScenarioOptions o;
  o.seed = 5;
  auto a = WriteScenarioFor(map, "m.yaml", o), b = WriteScenarioFor(map, "m.yaml", o);
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  ASSERT_TRUE(b.ok()) << b.status().ToString();
  EXPECT_EQ(sim::ScenarioToYaml(a->scenario, "m.yaml"), sim::ScenarioToYaml(b->scenario, "m.yaml"));
  o.seed = 6;
  auto c = WriteScenarioFor(map, "m.yaml", o);
  ASSERT_TRUE(c.ok());
  EXPECT_NE(sim::ScenarioToYaml(a->scenario, "m.yaml"), sim::ScenarioToYaml(c->scenario, "m.yaml"));
}

// Odometry that errs systematically, as the SLAM benchmark logs' own does, also in the file
// the suite hands to the evaluation.
TEST(ScenarioWriterTest, TheVehiclesOdometryErrsAsRealOdometryDoes) {
  const core::OccupancyGrid map = Warehouse(2);
  ScenarioOptions o;
  o.odometry_scale_sigma = 0.04;
  o.odometry_heading_drift_sigma_rad_m = 0.07;
  auto written = WriteScenarioFor(map, "m.yaml", o);
  ASSERT_TRUE(written.ok()) << written.status().ToString();
  auto reread = sim::ParseScenario(sim::ScenarioToYaml(written->scenario, "m.yaml"), "w");
  ASSERT_TRUE(reread.ok()) << reread.status().ToString();
  ASSERT_FALSE(reread->vehicles.empty());
  for (const sim::VehicleSpec& v : reread->vehicles) {
    EXPECT_EQ(v.odometry.scale_sigma, 0.04) << v.id;
    EXPECT_EQ(v.odometry.heading_drift_sigma_rad_m, 0.07) << v.id;
  }
  o.odometry_scale_sigma = -0.01;
  EXPECT_FALSE(WriteScenarioFor(map, "m.yaml", o).ok());
}

TEST(ScenarioWriterTest, WritesAScenarioForAPublicMapOfARealWarehouse) {
  const std::string rel = "worlds/mvsim_warehouse/mvsim_warehouse.yaml";
  FLEETMAP_SKIP_WITHOUT_DATA(rel);
  auto map = core::LoadMapServerMap(testing::DataPath(rel));
  ASSERT_TRUE(map.ok()) << map.status().ToString();
  ScenarioOptions o;
  o.vehicles = 2;
  auto s = WriteScenarioFor(map->grid, testing::DataPath(rel), o);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_EQ(s->scenario.vehicles.size(), 2u);
  EXPECT_TRUE(sim::World::Create(s->scenario, map->grid).ok());
}

// A shop of 15 x 15 m has no room for three vehicles' loops and a pallet beside each: the
// writer fits a smaller fleet and says so, or refuses with the reason when told not to.
TEST(ScenarioWriterTest, ASmallFloorGetsASmallerFleetAndSaysSo) {
  const std::string rel = "worlds/aws_bookstore/map.yaml";
  FLEETMAP_SKIP_WITHOUT_DATA(rel);
  auto map = core::LoadMapServerMap(testing::DataPath(rel));
  ASSERT_TRUE(map.ok()) << map.status().ToString();
  ScenarioOptions o;
  auto s = WriteScenarioFor(map->grid, testing::DataPath(rel), o);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_LT(s->scenario.vehicles.size(), 3u);
  EXPECT_THAT(s->fitted, HasSubstr("instead of 3"));
  EXPECT_FALSE(s->scenario.objects.empty());
  EXPECT_TRUE(sim::World::Create(s->scenario, map->grid).ok());
  o.fit_to_floor = false;
  auto refused = WriteScenarioFor(map->grid, testing::DataPath(rel), o);
  ASSERT_FALSE(refused.ok());
  EXPECT_THAT(refused.status().message(), HasSubstr("no room"));
}

TEST(ScenarioWriterTest, AMapWithoutRoomIsRefusedWithTheReason) {
  core::OccupancyGrid unknown(core::GridGeometry(0.05, 200, 200));  // nothing observed
  auto s = WriteScenarioFor(unknown, "m.yaml", ScenarioOptions{});
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.status().message(), HasSubstr("no free space"));
  ScenarioOptions bad;
  bad.vehicles = 9;
  EXPECT_THAT(WriteScenarioFor(unknown, "m.yaml", bad).status().message(),
              HasSubstr("vehicles must be 1 to 5"));
}

}  // namespace
}  // namespace fleetmap::sim::worldgen
