#include "eval/suite/suite_plan.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

namespace fleetmap::eval::suite {
namespace {

namespace fs = std::filesystem;

TEST(SuitePlanTest, TheFullSuiteHasFortyGeneratedWorldsOfEveryStyleResolutionAndTurn) {
  const SuitePlan plan = PlanSuite({});
  std::set<std::string> names, styles;
  std::set<double> resolutions, turns;
  int generated = 0;
  for (const SuiteWorld& w : plan.worlds) {
    EXPECT_TRUE(names.insert(w.name).second) << "two worlds named " << w.name;
    if (w.source != WorldSource::kGenerated) continue;
    ++generated;
    styles.insert(w.group);
    resolutions.insert(w.generated.render.resolution_m);
    turns.insert(w.generated.render.rotation_rad);
    EXPECT_TRUE(w.generated.Validate().ok()) << w.name;
  }
  EXPECT_GE(generated, 40);
  EXPECT_EQ(styles.size(), sim::worldgen::AllBuildingStyles().size());
  EXPECT_EQ(*resolutions.begin(), 0.02);
  EXPECT_EQ(*resolutions.rbegin(), 0.10);
  EXPECT_GE(turns.size(), 6u);
  // Without a worlds folder the public maps are left out, and the plan says so.
  ASSERT_EQ(plan.notes.size(), 1u);
  EXPECT_NE(plan.notes[0].find("public maps left out"), std::string::npos);
}

TEST(SuitePlanTest, TheQuickSuiteHasEveryStyleOnceAndTheLivingLabLast) {
  PlanOptions o;
  o.quick = true;
  o.livinglab_scenario = "fleet.yaml";
  const SuitePlan plan = PlanSuite(o);
  std::set<std::string> styles;
  for (const SuiteWorld& w : plan.worlds)
    if (w.source == WorldSource::kGenerated) styles.insert(w.group);
  EXPECT_EQ(styles.size(), sim::worldgen::AllBuildingStyles().size());
  EXPECT_LE(plan.worlds.size(), 6u);
  EXPECT_EQ(plan.worlds.back().source, WorldSource::kLivingLab);
  EXPECT_EQ(plan.worlds.back().scenario_yaml, "fleet.yaml");
}

TEST(SuitePlanTest, EveryFolderOfTheWorldsFolderIsAPublicMapEvenWithoutAYaml) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("suite_plan_" + std::to_string(getpid()));
  fs::create_directories(dir / "b_shop");
  fs::create_directories(dir / "a_hall");
  fs::create_directories(dir / "c_empty");
  std::ofstream(dir / "b_shop" / "map.yaml") << "image: map.pgm\n";
  std::ofstream(dir / "a_hall" / "hall.yaml") << "image: hall.pgm\n";
  std::ofstream(dir / "a_hall" / "notes.txt") << "not a map\n";
  PlanOptions o;
  o.worlds_dir = dir.string();
  const SuitePlan plan = PlanSuite(o);
  std::vector<const SuiteWorld*> maps;
  for (const SuiteWorld& w : plan.worlds)
    if (w.source == WorldSource::kPublic) maps.push_back(&w);
  ASSERT_EQ(maps.size(), 3u);
  EXPECT_EQ(maps[0]->name, "a_hall");
  EXPECT_EQ(fs::path(maps[0]->map_yaml).filename(), "hall.yaml");
  EXPECT_EQ(maps[1]->name, "b_shop");
  EXPECT_EQ(maps[2]->name, "c_empty");
  EXPECT_EQ(maps[2]->map_yaml, "");  // reported as unusable when prepared
  EXPECT_TRUE(plan.notes.empty());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fleetmap::eval::suite
