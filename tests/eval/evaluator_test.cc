#include "eval/evaluator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "eval/pipeline.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::eval {
namespace {

// A 10 m x 6 m room: a box that is there from the start, one that appears at 5 s and goes
// at 14 s, a person walking, one vehicle driving back and forth past all of them.
constexpr const char* kRoom = R"(
name: room
map: room.yaml
duration_s: 24
seed: 9
objects:
  - {id: box_a, rect: {center: [3, 1.5], size: [0.8, 0.6]}}
  - {id: box_b, rect: {center: [7, 4.5], size: [1.0, 0.8]}, appear_s: 5, disappear_s: 14}
actors:
  - {id: walker, radius_m: 0.3, path: [[8.5, 1.0], [8.5, 5.0]], speed_mps: 1.0, loop: true}
vehicles:
  - {id: v1, route: [[1, 3], [9, 3]], loop: true, speed_mps: 1.0}
)";

class EvaluatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    world_ = std::make_unique<sim::World>(
        sim::World::Create(sim::ParseScenario(kRoom, "room_scenario.yaml").value(),
                           sim::testing::Room())
            .value());
    simulator_ = std::make_unique<sim::Simulator>(world_.get());
    auto oracle = MakeOraclePipeline();
    run_ = RunScenario(*world_, *oracle, *simulator_);
  }
  EvalReport Score(const RunRecord& run) {
    return Evaluate(*world_, simulator_->observations(), run);
  }
  int64_t Index(double x, double y) const {
    return world_->geometry().Index(world_->geometry().WorldToCell({x, y}));
  }
  void SetCell(RunRecord& run, int64_t i, core::CellState s) {
    const int w = world_->geometry().width();
    run.final_map.SetState({int(i % w), int(i / w)}, s);
  }

  std::unique_ptr<sim::World> world_;
  std::unique_ptr<sim::Simulator> simulator_;
  RunRecord run_;
};

TEST_F(EvaluatorTest, OracleIsPerfect) {
  const EvalReport r = Score(run_);
  EXPECT_GT(r.changes.true_added, 20);    // box_a's visible faces
  EXPECT_GT(r.changes.true_removed, 20);  // box_b seen, then seen gone
  EXPECT_DOUBLE_EQ(r.changes.f1, 1.0);
  EXPECT_EQ(r.changes.static_cells_erased, 0);
  EXPECT_EQ(r.changes.actor_cells_mapped, 0);
  EXPECT_NEAR(r.align_translation_cells.max, 0.0, 1e-9);
  EXPECT_EQ(r.merges_rejected, 0);
}

TEST_F(EvaluatorTest, ShiftedMergeLowersF1AndShowsInAlignment) {
  RunRecord shifted = run_;
  // Move every added cell 4 cells (20 cm) along x: outside the 1-cell tolerance.
  core::OccupancyGrid moved = world_->static_map();
  const auto& g = world_->geometry();
  for (int64_t i = 0; i < g.num_cells(); ++i) {
    const bool added = run_.final_map.state({int(i % g.width()), int(i / g.width())}) ==
                           core::CellState::kOccupied &&
                       world_->static_map().cells()[i] <= 0;
    if (added)
      moved.SetState({int(i % g.width()) + 4, int(i / g.width())}, core::CellState::kOccupied);
  }
  shifted.final_map = moved;
  for (MergeRecord& m : shifted.merges) m.placed_origin.x_m += 0.2;
  const EvalReport r = Score(shifted);
  EXPECT_LT(r.changes.added_precision, 0.5);
  EXPECT_LT(r.changes.f1, 0.8);
  EXPECT_NEAR(r.align_translation_cells.median, 4.0, 1e-9);
  EXPECT_NEAR(r.align_translation_m.p95, 0.2, 1e-9);
}

// The anchor's error beside the placed one: whether the correction helped or hurt.
TEST_F(EvaluatorTest, AnchorErrorIsScoredBesideThePlacement) {
  RunRecord anchored = run_;
  ASSERT_FALSE(anchored.merges.empty());
  for (MergeRecord& m : anchored.merges) m.anchor_origin.y_m += 0.15;  // 3 cells off
  EXPECT_NEAR(Score(anchored).anchor_translation_cells.p95, 3.0, 1e-9);
  EXPECT_NEAR(Score(anchored).align_translation_cells.p95, 0.0, 1e-9);
  EXPECT_NEAR(Score(run_).anchor_translation_cells.max, 0.0, 1e-9);
}

// The builders' drift over every map, accepted or not; a run that does not know it gives none.
TEST_F(EvaluatorTest, TheBuildersDriftIsSummarizedWhereTheRunKnowsIt) {
  EXPECT_EQ(Score(run_).tempmap_drift_m.count, 0);
  EXPECT_NE(ReportJson(Score(run_)).find("\"tempmap.drift_m.p95\": null"), std::string::npos);
  RunRecord drifted = run_;
  ASSERT_FALSE(drifted.merges.empty());
  drifted.merges.front().drift_m = 0.04;
  drifted.merges.front().drift_deg = 0.3;
  MergeRecord rejected = drifted.merges.front();
  rejected.accepted = false;
  rejected.drift_m = 0.12;
  rejected.drift_deg = 0.7;
  drifted.merges.push_back(rejected);
  const EvalReport r = Score(drifted);
  EXPECT_EQ(r.tempmap_drift_m.count, 2);
  EXPECT_NEAR(r.tempmap_drift_m.max, 0.12, 1e-12);
  EXPECT_NEAR(r.tempmap_drift_deg.median, 0.5, 1e-12);
  EXPECT_NE(ReportJson(r).find("\"tempmap.drift_deg.max\": 0.7"), std::string::npos);
}

TEST_F(EvaluatorTest, ErasedWallIsCountedCellByCell) {
  RunRecord erased = run_;
  for (double x = 2.0; x < 2.5; x += 0.05) SetCell(erased, Index(x, 0.02), core::CellState::kFree);
  EXPECT_EQ(Score(erased).changes.static_cells_erased, 10);
}

TEST_F(EvaluatorTest, MappedPersonIsCaught) {
  RunRecord ghost = run_;
  // Three cells on the walker's path, far from walls and boxes.
  for (double y : {2.0, 2.5, 3.5}) SetCell(ghost, Index(8.5, y), core::CellState::kOccupied);
  const EvalReport r = Score(ghost);
  EXPECT_EQ(r.changes.actor_cells_mapped, 3);
  EXPECT_LT(r.changes.added_precision, 1.0);  // they are false additions too
}

TEST_F(EvaluatorTest, ObjectCellsLostToSeenFreeDropsAreCounted) {
  EXPECT_FALSE(Score(run_).changes.seen_free_drops.has_value());  // the oracle drops nothing
  EXPECT_NE(ReportJson(Score(run_)).find("\"seen_free.added_missed\": null"), std::string::npos);
  RunRecord watched = run_;
  watched.RecordSeenFreeDrops({Index(8.5, 2.5)});  // a person's turning point: no loss
  ChangeScores c = Score(watched).changes;
  EXPECT_EQ(c.seen_free_drops, 1);
  EXPECT_EQ(c.seen_free_drops_near_added, 0);
  EXPECT_EQ(c.added_missed_seen_free, 0);
  // box_a's cells dropped and never mapped again: each of them is a loss the drops caused.
  std::vector<int64_t> box;
  for (int64_t i = 0; i < world_->geometry().num_cells(); ++i) {
    const sim::CellObservations* o = simulator_->observations().Cell(i);
    const Eigen::Vector2d p = world_->geometry().CellCenter(
        {int(i % world_->geometry().width()), int(i / world_->geometry().width())});
    if (o && o->LastState() == core::CellState::kOccupied &&
        (p - Eigen::Vector2d(3, 1.5)).norm() < 1)
      box.push_back(i);
  }
  ASSERT_GT(box.size(), 20u);
  for (int64_t i : box) SetCell(watched, i, core::CellState::kFree);
  watched.RecordSeenFreeDrops(box);
  c = Score(watched).changes;
  EXPECT_EQ(c.seen_free_drops, int64_t(box.size()) + 1);
  EXPECT_EQ(c.seen_free_drops_near_added, int64_t(box.size()));
  EXPECT_EQ(c.added_missed_seen_free, int64_t(box.size()));
  EXPECT_LT(c.added_recall, 0.5);
}

TEST_F(EvaluatorTest, MissedRemovalLowersRecall) {
  RunRecord stale = run_;
  // Keep box_b in the map although it was seen gone.
  for (int64_t i = 0; i < world_->geometry().num_cells(); ++i) {
    const sim::CellObservations* o = simulator_->observations().Cell(i);
    if (o && o->ever_hit && o->LastState() == core::CellState::kFree)
      SetCell(stale, i, core::CellState::kOccupied);
  }
  const EvalReport r = Score(stale);
  EXPECT_DOUBLE_EQ(r.changes.removed_recall, 0.0);
  EXPECT_LT(r.changes.recall, 0.7);
}

TEST_F(EvaluatorTest, DetectionLatencyAndFalseTriggers) {
  const auto& obs = simulator_->observations();
  const double a_seen = obs.Seen(0, 0).appear_seen_s;     // box_a, there from the start
  const double b_seen = obs.Seen(1, 0).appear_seen_s;     // box_b appears at 5 s
  const double b_gone = obs.Seen(1, 0).disappear_seen_s;  // box_b goes at 14 s
  ASSERT_LT(a_seen, 1.0);
  ASSERT_GE(b_seen, 5.0);
  ASSERT_LT(b_seen, 6.0);
  ASSERT_GE(b_gone, 14.0);
  ASSERT_LT(b_gone, 20.0);
  // The vehicle builds a temporary map 0.4 s after it sees box_b gone, and once at 11 s,
  // when it saw no change in the 5 s before.
  RunRecord traced = run_;
  for (double t = 0.0; t < 24.0; t += 0.02) {
    const bool building = (t >= b_gone + 0.4 && t < b_gone + 2.0) || (t >= 11.0 && t < 11.5);
    traced.divergence.push_back({"v1", t, 0.5, 0.5, 0.4, building ? 0.2 : 0.0, building});
  }
  EvalOptions options;
  options.trigger_window_s = 5.0;
  options.detection_window_s = 5.0;
  const EvalReport r = Evaluate(*world_, obs, traced, options);
  EXPECT_EQ(r.changes_seen, 3);
  EXPECT_EQ(r.changes_detected, 1);
  EXPECT_NEAR(r.detection_latency_s.median, 0.4, 0.021);
  EXPECT_EQ(r.false_triggers, 1);
  // A map open from a vehicle's first sample on (DivergenceOptions::map_at_start) is no
  // trigger: here the vehicle's samples begin at 12 s, when it had seen no change for 5 s.
  RunRecord late = run_;
  for (double t = 12.0; t < 24.0; t += 0.02) {
    const bool building = t < 12.5 || (t >= b_gone + 0.4 && t < b_gone + 2.0);
    late.divergence.push_back({"v1", t, 0.5, 0.5, 0.4, building ? 0.2 : 0.0, building});
  }
  const EvalReport at_start = Evaluate(*world_, obs, late, options);
  EXPECT_EQ(at_start.changes_detected, 1);
  EXPECT_EQ(at_start.false_triggers, 0);
}

TEST_F(EvaluatorTest, ReportJsonHasTheStableKeys) {
  const std::string json = ReportJson(Score(run_));
  for (const char* key :
       {"\"changed_cells.precision\"", "\"changed_cells.recall\"", "\"changed_cells.f1\"",
        "\"static_cells_erased\"", "\"actor_cells_mapped\"", "\"alignment.translation_m.median\"",
        "\"alignment.translation_m.p95\"", "\"alignment.rotation_deg.median\"",
        "\"alignment.rotation_deg.p95\"", "\"detection.latency_s.median\"",
        "\"detection.false_triggers\""}) {
    EXPECT_NE(json.find(key), std::string::npos) << key;
  }
  EXPECT_NE(json.find("\"detection.latency_s.median\": null"), std::string::npos);
}

// Names come from outside (a scenario file, channel names in a log): report.json stays JSON
// whatever they hold, and the extra keys follow the report's own.
TEST_F(EvaluatorTest, ReportJsonIsJsonWhateverTheNamesHold) {
  EvalReport r = Score(run_);
  r.scenario = "hall \"B\" \\ east\n";
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(
      ReportJson(r, {{"fleet.final_version", "12"}, {"fleet.bytes_per_s.TEMPMAP_\"x\"", "null"}}));
  EXPECT_EQ(json["scenario"], r.scenario);
  EXPECT_EQ(json["fleet.final_version"], 12);
  EXPECT_TRUE(json["fleet.bytes_per_s.TEMPMAP_\"x\""].is_null());
  EXPECT_EQ(json.begin().key(), "scenario");
  EXPECT_EQ((--json.end()).key(), "fleet.bytes_per_s.TEMPMAP_\"x\"");
}

// A run in which nothing changed has no changed-cell score: F1, precision and recall are
// undefined (null in report.json), not a perfect 1.
TEST(EvaluatorNothingChangedTest, ScoresAreUndefinedNotPerfect) {
  constexpr const char* kStill = R"(
name: still
map: room.yaml
duration_s: 6
seed: 9
vehicles:
  - {id: v1, route: [[1, 3], [9, 3]], loop: true, speed_mps: 1.0}
)";
  sim::World world =
      sim::World::Create(sim::ParseScenario(kStill, "still.yaml").value(), sim::testing::Room())
          .value();
  sim::Simulator simulator(&world);
  auto oracle = MakeOraclePipeline();
  const RunRecord run = RunScenario(world, *oracle, simulator);
  const EvalReport r = Evaluate(world, simulator.observations(), run);
  EXPECT_EQ(r.changes.true_added + r.changes.true_removed, 0);
  EXPECT_EQ(r.changes.predicted_added + r.changes.predicted_removed, 0);
  EXPECT_TRUE(std::isnan(r.changes.f1));
  EXPECT_TRUE(std::isnan(r.changes.precision));
  EXPECT_TRUE(std::isnan(r.changes.recall));
  EXPECT_NE(ReportJson(r).find("\"changed_cells.f1\": null"), std::string::npos);
}

// A map that shows none of the changes scores 0, with its precision undefined.
TEST_F(EvaluatorTest, AMapWithoutTheChangesScoresZero) {
  RunRecord blind = run_;
  blind.final_map = world_->static_map();
  blind.ever_occupied.clear();
  const EvalReport r = Score(blind);
  ASSERT_GT(r.changes.true_added, 0);
  EXPECT_EQ(r.changes.predicted_added + r.changes.predicted_removed, 0);
  EXPECT_DOUBLE_EQ(r.changes.f1, 0.0);
  EXPECT_DOUBLE_EQ(r.changes.recall, 0.0);
  EXPECT_TRUE(std::isnan(r.changes.precision));
}

}  // namespace
}  // namespace fleetmap::eval
