#include "eval/suite/world_preparation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/map/map_io.h"
#include "sim/scenario.h"

namespace fleetmap::eval::suite {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string Folder(const std::string& name) {
  return (fs::path(::testing::TempDir()) / ("suite_prep_" + name + std::to_string(getpid())))
      .string();
}

TEST(WorldPreparationTest, UnusableMapsAreRefusedWithTheReason) {
  core::OccupancyGrid unknown(core::GridGeometry(0.05, 100, 100));
  EXPECT_THAT(CheckMapUsable(unknown).message(), HasSubstr("every cell is unknown"));
  EXPECT_THAT(CheckMapUsable(core::OccupancyGrid(core::GridGeometry(0.05, 0, 0))).message(),
              HasSubstr("no cells"));
  core::OccupancyGrid walls_only(core::GridGeometry(0.05, 20, 20));
  walls_only.SetState(core::CellIndex{3, 3}, core::CellState::kOccupied);
  EXPECT_THAT(CheckMapUsable(walls_only).message(), HasSubstr("free floor"));
  core::OccupancyGrid floor_only(core::GridGeometry(0.05, 100, 100));
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x)
      floor_only.SetState(core::CellIndex{x, y}, core::CellState::kFree);
  EXPECT_THAT(CheckMapUsable(floor_only).message(), HasSubstr("no occupied cell"));
}

TEST(WorldPreparationTest, APublicMapWhoseImageDoesNotLoadIsUnusable) {
  const std::string folder = Folder("bad_image");
  fs::create_directories(folder);
  std::ofstream(folder + "/map.yaml")
      << "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
         "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  std::ofstream(folder + "/map.pgm") << "P5 not an image";
  SuiteWorld w;
  w.name = "bad_image";
  w.source = WorldSource::kPublic;
  w.map_yaml = folder + "/map.yaml";
  auto p = PrepareWorld(w, folder + "/out", {});
  ASSERT_FALSE(p.ok());
  EXPECT_THAT(p.status().ToString(), HasSubstr("map.pgm"));
  w.map_yaml = "";
  EXPECT_THAT(PrepareWorld(w, folder + "/out", {}).status().message(),
              HasSubstr("no single map_server YAML"));
  fs::remove_all(folder);
}

TEST(WorldPreparationTest, AGeneratedWorldGetsItsMapAndAScenarioOnIt) {
  SuiteWorld w;
  w.name = "g_office_1";
  w.source = WorldSource::kGenerated;
  w.generated.style = sim::worldgen::BuildingStyle::kOffice;
  w.generated.length_m = 30;
  w.generated.width_m = 18;
  w.generated.render.resolution_m = 0.08;
  const std::string folder = Folder("generated");
  sim::worldgen::ScenarioOptions scenario;
  scenario.duration_s = 120;
  auto p = PrepareWorld(w, folder, scenario);
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  EXPECT_DOUBLE_EQ(p->resolution_m, 0.08);
  EXPECT_GT(p->width_m, 30.0);
  auto s = sim::LoadScenario(p->scenario_yaml);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_EQ(s->name, "g_office_1");
  EXPECT_DOUBLE_EQ(s->duration_s, 120);
  EXPECT_TRUE(core::LoadMapServerMap(s->map_yaml).ok());
  EXPECT_TRUE(fs::exists(folder + "/map.png"));
  fs::remove_all(folder);
}

}  // namespace
}  // namespace fleetmap::eval::suite
