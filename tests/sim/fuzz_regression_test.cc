// Scenarios on which fuzz/scenario_fuzz.cc found ParseScenario throwing (an uncaught yaml-cpp
// exception aborts fleetmap-sim); the fuzzer's own inputs are in tests/data/fuzz/scenario/.
// Fixed in core/yaml_reader.{h,cc} and sim/scenario_loader.cc.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/io/file_io.h"
#include "sim/scenario.h"

namespace fleetmap::sim {
namespace {

using ::testing::HasSubstr;

std::string Fixture(const std::string& name) {
  auto bytes =
      core::ReadFileBytes(FLEETMAP_SOURCE_DIR "/tests/data/fuzz/scenario/" + name, 1 << 20);
  EXPECT_TRUE(bytes.ok());
  return bytes.ok() ? *bytes : std::string();
}

TEST(ScenarioFuzzRegressionTest, RectWithoutAMapIsAnError) {
  // "rect:" with no value: rect["center"] is an invalid node, and yaml-cpp threw InvalidNode.
  auto null_rect = ParseScenario(Fixture("rect_null"), "s.yaml");
  EXPECT_THAT(null_rect.status().message(), HasSubstr("objects[0].rect"));
  // "rect: r": a key looked up in a scalar, and yaml-cpp threw BadSubscript.
  auto scalar_rect = ParseScenario(Fixture("rect_scalar"), "s.yaml");
  EXPECT_THAT(scalar_rect.status().message(), HasSubstr("objects[0].rect"));
}

TEST(ScenarioFuzzRegressionTest, MissingListsAreErrorsNotExceptions) {
  // The same invalid node for any list that is not there at all.
  auto no_route = ParseScenario("map: m.yaml\nvehicles:\n  - {id: v1}\n", "s.yaml");
  EXPECT_THAT(no_route.status().message(), HasSubstr("vehicles[0].route"));
  auto no_path = ParseScenario(
      "map: m.yaml\nactors:\n  - {id: a}\nvehicles:\n  - {id: v1, route: [[0, 0], [1, 0]]}\n",
      "s.yaml");
  EXPECT_THAT(no_path.status().message(), HasSubstr("actors[0].path"));
}

}  // namespace
}  // namespace fleetmap::sim
