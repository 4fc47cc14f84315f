#include "sim/worldgen/world_generator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/map/map_io.h"

namespace fleetmap::sim::worldgen {
namespace {

using core::CellState;
using ::testing::HasSubstr;

WorldOptions Options(BuildingStyle style, uint64_t seed, double length_m, double width_m) {
  WorldOptions o;
  o.style = style;
  o.seed = seed;
  o.length_m = length_m;
  o.width_m = width_m;
  return o;
}

double Share(const core::OccupancyGrid& g, CellState s) {
  return static_cast<double>(g.CountState(s)) / g.geometry().num_cells();
}

// The direction of the longest straight run of occupied cells (a wall, a rack's face), in
// degrees within [0, 90): the angle of the building, whichever of its two axes.
double DominantWallAngleDeg(const core::OccupancyGrid& g) {
  const auto& geo = g.geometry();
  cv::Mat occupied(geo.height(), geo.width(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < geo.height(); ++y)
    for (int x = 0; x < geo.width(); ++x)
      if (g.state({x, y}) == CellState::kOccupied) occupied.at<uint8_t>(y, x) = 255;
  std::vector<cv::Vec2f> lines;  // (rho, theta), strongest first
  cv::HoughLines(occupied, lines, 1.0, M_PI / 720, 100);
  if (lines.empty()) return -1.0;
  const double deg = lines[0][1] * 180.0 / M_PI;  // the line's normal: the same modulo 90
  return std::fmod(deg, 90.0);
}

TEST(WorldGeneratorTest, TheSameSeedGivesTheSameMapAndAnotherSeedAnother) {
  const WorldOptions o = Options(BuildingStyle::kOffice, 7, 30, 20);
  auto a = GenerateWorld(o);
  auto b = GenerateWorld(o);
  ASSERT_TRUE(a.ok() && b.ok()) << a.status().ToString();
  EXPECT_EQ(a->map.grid.cells(), b->map.grid.cells());
  WorldOptions other = o;
  other.seed = 8;
  auto c = GenerateWorld(other);
  ASSERT_TRUE(c.ok());
  EXPECT_NE(a->map.grid.cells(), c->map.grid.cells());
}

TEST(WorldGeneratorTest, EveryStyleLooksLikeASlamMapAndSurvivesItsFiles) {
  for (BuildingStyle style : AllBuildingStyles()) {
    SCOPED_TRACE(BuildingStyleName(style));
    auto w = GenerateWorld(Options(style, 3, 40, 25));
    ASSERT_TRUE(w.ok()) << w.status().ToString();
    const core::OccupancyGrid& g = w->map.grid;
    // Free floor inside; walls and furniture seen as surfaces; unknown around the building
    // and inside solid things.
    EXPECT_GT(Share(g, CellState::kFree), 0.35);
    EXPECT_GT(Share(g, CellState::kOccupied), 0.005);
    EXPECT_LT(Share(g, CellState::kOccupied), 0.25);
    EXPECT_GT(Share(g, CellState::kUnknown), 0.05);
    const auto& geo = g.geometry();
    for (core::CellIndex corner :
         {core::CellIndex{0, 0}, core::CellIndex{geo.width() - 1, 0},
          core::CellIndex{0, geo.height() - 1}, core::CellIndex{geo.width() - 1, geo.height() - 1}})
      EXPECT_EQ(g.state(corner), CellState::kUnknown);
    // The building's extent is what was asked, plus the unknown margin.
    EXPECT_NEAR(geo.width() * geo.resolution_m(), 40 + 1.0 + 2 * 1.5, 0.1);

    const std::string path = ::testing::TempDir() + "worldgen_" + BuildingStyleName(style) +
                             std::to_string(getpid()) + ".yaml";
    ASSERT_TRUE(core::SaveMapServerMap(g, path).ok());
    auto loaded = core::LoadMapServerMap(path);
    ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
    for (CellState s : {CellState::kFree, CellState::kOccupied, CellState::kUnknown})
      EXPECT_EQ(loaded->grid.CountState(s), g.CountState(s));
  }
}

TEST(WorldGeneratorTest, ATurnedBuildingsWallsComeOutAtTheAskedAngle) {
  for (double deg : {0.0, 17.0, 35.0, 62.0}) {
    SCOPED_TRACE(deg);
    WorldOptions o = Options(BuildingStyle::kRackedWarehouse, 5, 50, 30);
    o.render.rotation_rad = deg * M_PI / 180.0;
    auto w = GenerateWorld(o);
    ASSERT_TRUE(w.ok()) << w.status().ToString();
    const double measured = DominantWallAngleDeg(w->map.grid);
    const double error = std::fmod(std::abs(measured - deg) + 45.0, 90.0) - 45.0;
    EXPECT_LT(std::abs(error), 1.0) << "measured " << measured;
  }
}

TEST(WorldGeneratorTest, TheSameBuildingAtAnyResolutionHasTheSameSizeInMetres) {
  for (double res : {0.02, 0.05, 0.10}) {
    SCOPED_TRACE(res);
    WorldOptions o = Options(BuildingStyle::kHospital, 2, 60, 18);
    o.render.resolution_m = res;
    auto w = GenerateWorld(o);
    ASSERT_TRUE(w.ok()) << w.status().ToString();
    const auto& geo = w->map.grid.geometry();
    EXPECT_NEAR(geo.width() * res, 60 + 1.0 + 3.0, res);
    EXPECT_NEAR(geo.height() * res, 18 + 1.0 + 3.0, res);
    // Free floor is the same share of the grid whatever the cell size.
    EXPECT_NEAR(Share(w->map.grid, CellState::kFree), 0.6, 0.2);
  }
}

TEST(WorldGeneratorTest, OptionsOutOfRangeAreRefusedByName) {
  WorldOptions o = Options(BuildingStyle::kOffice, 1, 30, 20);
  o.render.resolution_m = 0.0;
  EXPECT_THAT(GenerateWorld(o).status().message(), HasSubstr("resolution_m"));
  o = Options(BuildingStyle::kOffice, 1, 5, 20);
  EXPECT_THAT(GenerateWorld(o).status().message(), HasSubstr("length_m"));
  o = Options(BuildingStyle::kOffice, 1, 30, 200);
  EXPECT_THAT(GenerateWorld(o).status().message(), HasSubstr("width_m"));
  o = Options(BuildingStyle::kOffice, 1, 30, 20);
  o.render.rotation_rad = std::nan("");
  EXPECT_THAT(GenerateWorld(o).status().message(), HasSubstr("rotation_rad"));
  EXPECT_THAT(ParseBuildingStyle("castle").status().message(), HasSubstr("racked_warehouse"));
}

}  // namespace
}  // namespace fleetmap::sim::worldgen
