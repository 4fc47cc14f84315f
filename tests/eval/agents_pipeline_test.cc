#include "tools/eval/agents_pipeline.h"

#include <gtest/gtest.h>

#include "tests/sim/sim_test_util.h"
#include "tools/eval/evaluator.h"

namespace fleetmap::eval {
namespace {

// A 10 m x 6 m room: a box there from the start, one that appears at 5 s and goes at 40 s;
// one vehicle drives back and forth past both.
constexpr const char* kRoom = R"(
name: room
map: room.yaml
duration_s: 70
seed: 4
objects:
  - {id: box_a, rect: {center: [3, 1.5], size: [0.8, 0.6]}}
  - {id: box_b, rect: {center: [7, 4.5], size: [1.0, 0.8]}, appear_s: 5, disappear_s: 40}
vehicles:
  - {id: v1, route: [[1.013, 3.027], [9.013, 3.027]], loop: true, speed_mps: 1.0}
)";

TEST(AgentsPipelineTest, TheRealSystemInProcessMapsWhatChanged) {
  const sim::World world =
      sim::World::Create(sim::ParseScenario(kRoom, "room.yaml").value(), sim::testing::Room())
          .value();
  auto pipeline = MakeAgentsPipeline(world);
  ASSERT_TRUE(pipeline.ok()) << pipeline.status().ToString();
  sim::Simulator simulator(&world);
  const RunRecord run = RunScenario(world, **pipeline, simulator);
  const EvalReport report = Evaluate(world, simulator.observations(), run);
  // Several short temporary maps (3 s each), every one placed within the goal; box_b added
  // and removed again, box_a added; no wall touched.
  EXPECT_GT(report.merges_accepted, 3);
  EXPECT_LE(report.align_translation_cells.p95, 1.5);
  EXPECT_GE(report.changes.f1, 0.9);
  EXPECT_GT(report.changes.true_removed, 0);
  EXPECT_GE(report.changes.removed_recall, 0.9);
  EXPECT_EQ(report.changes.static_cells_erased, 0);
}

}  // namespace
}  // namespace fleetmap::eval
