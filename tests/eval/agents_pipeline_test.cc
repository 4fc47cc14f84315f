#include "eval/agents_pipeline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "eval/evaluator.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::eval {
namespace {

constexpr const char* kRoom = sim::testing::kRoomWithBoxesScenario;

// The room with the seed of its random streams replaced: which temporary maps see which
// face of a box varies from run to run
// (docs/experiments/2026-12-07-split-maps-anchored-at-their-first-scan.md).
EvalReport RunRoom(uint32_t seed) {
  sim::Scenario scenario = sim::ParseScenario(kRoom, "room.yaml").value();
  scenario.seed = seed;
  const sim::World world = sim::World::Create(scenario, sim::testing::Room()).value();
  auto pipeline = MakeAgentsPipeline(world);
  EXPECT_TRUE(pipeline.ok()) << pipeline.status().ToString();
  if (!pipeline.ok()) return {};
  sim::Simulator simulator(&world);
  const RunRecord run = RunScenario(world, **pipeline, simulator);
  return Evaluate(world, simulator.observations(), run);
}

TEST(AgentsPipelineTest, TheRealSystemInProcessMapsWhatChanged) {
  // Several short temporary maps (3 s each), every one placed within the goal; box_b added
  // and removed again, box_a added; no wall touched. Not all of box_b in every run: a side
  // face seen in a single temporary map is never confirmed (confirmations = 2), so never in
  // the map to be removed (0.22 to 1 of box_b's seen cells over these seeds; a quarter of it is
  // one side face), so the level is judged over five runs, each run only for doing it at all.
  std::vector<double> f1, removed_recall;
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    const EvalReport report = RunRoom(seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_GT(report.merges_accepted, 3);
    EXPECT_LE(report.align_translation_cells.p95, 1.5);
    EXPECT_GE(report.changes.f1, 0.7);
    EXPECT_GT(report.changes.true_removed, 0);
    EXPECT_GT(report.changes.removed_recall, 0.0);
    EXPECT_EQ(report.changes.static_cells_erased, 0);
    f1.push_back(report.changes.f1);
    removed_recall.push_back(report.changes.removed_recall);
    std::printf("seed %u: F1 %.3f, removed recall %.3f, alignment p95 %.2f cells\n", seed,
                report.changes.f1, report.changes.removed_recall,
                report.align_translation_cells.p95);
  }
  std::sort(f1.begin(), f1.end());
  std::sort(removed_recall.begin(), removed_recall.end());
  EXPECT_GE(f1[2], 0.9);  // the medians
  EXPECT_GE(removed_recall[2], 0.75);
}

}  // namespace
}  // namespace fleetmap::eval
