#include "sim/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "sim/world.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::sim {
namespace {

using ::testing::HasSubstr;

constexpr const char* kGood = R"(
name: tiny
map: room.yaml
duration_s: 20
objects:
  - {id: box, rect: {center: [5, 3], size: [1, 1]}, appear_s: 5}
vehicles:
  - id: v1
    route: [[1, 1], [9, 1]]
)";

TEST(ScenarioTest, ParsesAndAppliesDefaults) {
  auto s = ParseScenario(kGood, "/worlds/tiny.yaml");
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_EQ(s->map_yaml, "/worlds/room.yaml");
  ASSERT_EQ(s->vehicles.size(), 1u);
  EXPECT_EQ(s->vehicles[0].scanner.name, "S300");
  EXPECT_EQ(s->vehicles[0].scanner.num_beams, 541);
  EXPECT_DOUBLE_EQ(s->vehicles[0].motion.speed_mps, 0.5);
  EXPECT_TRUE(s->objects[0].PresentAt(5.0));
  EXPECT_FALSE(s->objects[0].PresentAt(4.9));
}

struct BadCase {
  std::string yaml;
  std::string message;
};

class ScenarioErrorTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(ScenarioErrorTest, NamesFileLineAndField) {
  auto s = ParseScenario(GetParam().yaml, "bad.yaml");
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.status().message(), HasSubstr(GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ScenarioErrorTest,
    ::testing::Values(
        BadCase{"duration_s: 3\nvehicles: []\n", "bad.yaml:1: map: missing"},
        BadCase{"map: m.yaml\nvehicles:\n  - id: v\n    scanner: S301\n    route: [[0,0],[1,0]]\n",
                "bad.yaml:4: vehicles[0].scanner: unknown scanner model 'S301'"},
        BadCase{"map: m.yaml\nvehicles:\n  - id: v\n    speed_mps: -1\n    route: [[0,0],[1,0]]\n",
                "bad.yaml:4: vehicles[0].speed_mps: must be positive"},
        BadCase{"map: m.yaml\nvehicles:\n  - id: v\n    route: [[0,0]]\n",
                "vehicles[0].route: must be a list of at least 2"},
        BadCase{
            "map: m.yaml\nobjects:\n  - {id: p}\nvehicles:\n  - {id: v, route: [[0,0],[1,0]]}\n",
            "bad.yaml:3: objects[0]: needs a 'rect' or a 'polygon'"},
        BadCase{"map: m.yaml\nvehicles:\n  - {id: v, route: [[0,0],[1,0]]}\n  - {id: v, route: "
                "[[0,0],[1,0]]}\n",
                "vehicles[1].id: 'v' is used twice"},
        BadCase{"map: m.yaml\nvehicles:\n  - id: v\n    route: [[0,0],[1,0]]\n"
                "    odometry_noise: {scale_sigma: -0.01}\n",
                "bad.yaml:5: vehicles[0].odometry_noise.scale_sigma: must be >= 0"},
        BadCase{"map: [unclosed\n", "bad.yaml:"}));

Scenario Tiny() { return ParseScenario(kGood, "tiny.yaml").value(); }

TEST(WorldTest, RejectsObjectsOutsideTheMap) {
  Scenario s = Tiny();
  s.objects[0].polygon_m = RectanglePolygon({12.0, 3.0}, {1, 1}, 0);
  auto w = World::Create(s, testing::Room());
  ASSERT_FALSE(w.ok());
  // The field the file used (a rect), the object's extent and the map's.
  EXPECT_THAT(w.status().message(),
              HasSubstr("tiny.yaml:6: objects[0].rect: object 'box' spans x 11.50..12.50 m, "
                        "y 2.50..3.50 m, beyond the map (x 0.00..10.00 m, y 0.00..6.00 m)"));
}

TEST(WorldTest, RejectsAPersonWalkingThroughAnObject) {
  Scenario s = Tiny();  // the box covers x 4.5..5.5 m, y 2.5..3.5 m
  DynamicActor person;
  person.id = "p1";
  person.path_m = {{1.0, 2.1}, {9.0, 2.1}};  // 0.4 m from the box: clear with radius 0.25 m
  person.line = 11;
  s.actors.push_back(person);
  EXPECT_TRUE(World::Create(s, testing::Room()).ok());
  s.actors[0].radius_m = 0.5;  // now it touches the box
  auto w = World::Create(s, testing::Room());
  ASSERT_FALSE(w.ok());
  EXPECT_THAT(w.status().message(),
              HasSubstr("tiny.yaml:11: actors[0].path leg 0: person 'p1' (radius 0.50 m) runs "
                        "into object 'box' at (4."));
}

TEST(ScenarioTest, WrittenAsYamlItReadsBackTheSame) {
  Scenario s = ParseScenario(testing::kRoomWithBoxesScenario, "/w/room_scenario.yaml").value();
  DynamicActor forklift;
  forklift.id = "f1";
  forklift.kind = "forklift";
  forklift.radius_m = 0.8;
  forklift.path_m = {{1, 5}, {9, 5}};
  forklift.motion.loop = true;
  forklift.motion.dwell_s = 4;
  s.actors.push_back(forklift);
  s.vehicles[0].scanner = FindScannerModel("TiM571").value();
  s.vehicles[0].odometry.trans_per_trans = 0.03;
  s.vehicles[0].odometry.heading_drift_sigma_rad_m = 0.04;
  auto back = ParseScenario(ScenarioToYaml(s, "room.yaml"), "/w/room_scenario.yaml");
  ASSERT_TRUE(back.ok()) << back.status().ToString() << "\n" << ScenarioToYaml(s, "room.yaml");
  EXPECT_EQ(back->map_yaml, "/w/room.yaml");
  EXPECT_EQ(back->duration_s, 70);
  EXPECT_EQ(back->seed, 4u);
  ASSERT_EQ(back->objects.size(), 2u);
  EXPECT_EQ(back->objects[1].id, "box_b");
  EXPECT_EQ(back->objects[1].appear_s, 5);
  EXPECT_EQ(back->objects[1].disappear_s, 40);
  EXPECT_FALSE(std::isfinite(back->objects[0].disappear_s));
  for (size_t i = 0; i < 4; ++i)
    EXPECT_NEAR((back->objects[1].polygon_m[i] - s.objects[1].polygon_m[i]).norm(), 0, 1e-3);
  ASSERT_EQ(back->actors.size(), 1u);
  EXPECT_EQ(back->actors[0].kind, "forklift");
  EXPECT_EQ(back->actors[0].motion.dwell_s, 4);
  EXPECT_TRUE(back->actors[0].motion.loop);
  ASSERT_EQ(back->vehicles.size(), 1u);
  EXPECT_EQ(back->vehicles[0].scanner.name, "TiM571");
  EXPECT_EQ(back->vehicles[0].route_m, s.vehicles[0].route_m);
  EXPECT_EQ(back->vehicles[0].motion.speed_mps, 1.0);
  EXPECT_EQ(back->vehicles[0].odometry.trans_per_trans, 0.03);
  EXPECT_EQ(back->vehicles[0].odometry.heading_drift_sigma_rad_m, 0.04);
  EXPECT_EQ(back->vehicles[0].odometry.rot_per_rot, OdometryNoise().rot_per_rot);
  // A vehicle with the default odometry gets no odometry_noise in the file.
  s.vehicles[0].odometry = OdometryNoise();
  EXPECT_EQ(ScenarioToYaml(s, "room.yaml").find("odometry_noise"), std::string::npos);
}

TEST(WorldTest, RejectsARouteThroughAWall) {
  Scenario s = Tiny();
  auto room = testing::Room();
  for (int y = 0; y < 120; ++y) room.SetState({100, y}, core::CellState::kOccupied);
  auto w = World::Create(s, room);
  ASSERT_FALSE(w.ok());
  EXPECT_THAT(w.status().message(),
              HasSubstr("tiny.yaml:8: vehicles[0].route leg 0: runs through a wall"));
}

TEST(WorldTest, RejectsAMissingMapNamingTheScenario) {
  auto w = World::Load(testing::LivingLabDir() + "does_not_exist.yaml");
  ASSERT_FALSE(w.ok());
  EXPECT_THAT(w.status().message(), HasSubstr("does_not_exist.yaml"));
}

TEST(WorldTest, TruthFollowsAppearTimes) {
  auto w = World::Create(Tiny(), testing::Room());
  ASSERT_TRUE(w.ok()) << w.status().ToString();
  const auto before = w->TrueMapAt(4.0), after = w->TrueMapAt(6.0);
  EXPECT_EQ(before.state(before.geometry().WorldToCell({5.0, 3.0})), core::CellState::kFree);
  EXPECT_EQ(after.state(after.geometry().WorldToCell({5.0, 3.0})), core::CellState::kOccupied);
  EXPECT_EQ(w->object_cells()[0].size(), 400u);  // 1 m x 1 m at 5 cm
  EXPECT_EQ(w->ChangeTimes(), std::vector<double>{5.0});
  const auto events = w->ChangeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].t_s, 5.0);
  EXPECT_TRUE(events[0].added);
}

TEST(WorldTest, ShippedLivingLabScenariosLoad) {
  for (const char* name : {"addition.yaml", "removal.yaml", "fleet.yaml"}) {
    auto w = World::Load(testing::LivingLabDir() + name);
    ASSERT_TRUE(w.ok()) << name << ": " << w.status().ToString();
    EXPECT_EQ(w->geometry().width(), 1200);
    EXPECT_EQ(w->geometry().height(), 360);
  }
}

}  // namespace
}  // namespace fleetmap::sim
