// The divergence detector behind the localizer, on simulated drives through the LivingLab.
#include <gtest/gtest.h>

#include <string>

#include "tests/vehicle_agent/agent_sim_util.h"

namespace fleetmap::vehicle_agent {
namespace {

using sim_testing::RunOptions;
using sim_testing::RunVehicle;
using sim_testing::SimRun;
using sim_testing::Starts;

// What d opens, whatever the default of the map at start-up (tested below).
RunOptions DivergenceAlone() {
  RunOptions o;
  o.divergence.map_at_start = false;
  return o;
}

// One pallet put down beside the aisle, about 5 m ahead of the vehicle, while it drives.
std::string NewPalletScenario(const std::string& route, const std::string& pallet_rect,
                              double appear_s) {
  return "map: livinglab.yaml\nduration_s: " + std::to_string(appear_s + 10.0) +
         "\nseed: 8\nobjects:\n  - {id: pallet, rect: " + pallet_rect +
         ", appear_s: " + std::to_string(appear_s) +
         "}\nvehicles:\n  - id: v\n    scanner_mount: [0.3, 0.0, 0.0]\n    route: " + route + "\n";
}

TEST(DivergenceSimTest, OpensATemporaryMapWithinASecondOfANewPalletComingIntoView) {
  const std::string cases[][3] = {
      // Lower aisle eastwards; the pallet appears at 20 s, 5 m ahead and 1.5 m to the left.
      {"[[5.0, 4.0], [55.0, 4.0]]", "{center: [20.0, 5.5], size: [1.2, 0.8]}", "20"},
      // Upper aisle westwards; at 30 s, 5.5 m ahead and 1.3 m to the left (south).
      {"[[55.0, 13.5], [5.0, 13.5]]", "{center: [34.5, 12.2], size: [0.8, 1.2]}", "30"},
  };
  for (const auto& c : cases) {
    const double appear_s = std::stod(c[2]);
    const sim::World world = sim_testing::MakeWorld(NewPalletScenario(c[0], c[1], appear_s));
    const SimRun run = RunVehicle(world, DivergenceAlone());
    const double seen_s = run.seen[0].appear_seen_s;  // the first beam on the pallet
    ASSERT_FALSE(std::isnan(seen_s)) << c[1] << " never seen";
    EXPECT_NEAR(seen_s, appear_s, 0.05) << c[1] << " not in view when it appeared";
    const std::vector<double> starts = Starts(run);
    ASSERT_FALSE(starts.empty()) << c[1] << ": no temporary map";
    EXPECT_GE(starts.front(), seen_s) << c[1] << ": a map before anything changed";
    EXPECT_LE(starts.front() - seen_s, 1.0) << c[1];
  }
}

// Temporary maps that hysteresis at 0.1 / 0.05 (the defaults before the merge needed the
// parked robots seen) opens on the run's W_avg.
int64_t StartsAtTenPercent(const SimRun& run) {
  DivergenceOptions o;
  o.start_above = 0.1;
  o.stop_below = 0.05;
  o.min_duration_s = 2.0;
  o.map_at_start = false;
  DivergenceDetector detector(o);
  for (const auto& r : run.scans) detector.Update(r.stamp_s, r.stats.w_avg, r.omega_radps);
  return detector.stats().starts;
}

// The unchanged hall: no objects, the paper's five-minute loop (four corners).
constexpr const char* kUnchangedHall = R"(
map: livinglab.yaml
duration_s: 300
seed: 9
vehicles:
  - id: v
    scanner_mount: [0.3, 0.0, 0.0]
    route: [[5.0, 4.0], [55.0, 4.0], [55.0, 13.5], [5.0, 13.5]]
    loop: true
)";

TEST(DivergenceSimTest, StaysQuietInAnUnchangedHallForFiveMinutes) {
  const sim::World world = sim_testing::MakeWorld(kUnchangedHall);
  const SimRun run = RunVehicle(world, DivergenceAlone());
  ASSERT_GE(run.scans.back().stamp_s, 299.0);
  // The defaults (0.05 / 0.025, chosen for the merge's sake) may open a rare false map;
  // hysteresis at 0.1 / 0.05 on the same W_avg opens none.
  EXPECT_LE(run.divergence.starts, 3);
  EXPECT_EQ(StartsAtTenPercent(run), 0);
  EXPECT_EQ(run.divergence.samples, static_cast<int64_t>(run.scans.size()));
  // The paper's rule on the same W_avg opens a map at every flicker of d.
  DivergenceOptions paper;
  paper.rule = DivergenceRule::kPaper;
  DivergenceDetector detector(paper);
  for (const auto& r : run.scans) detector.Update(r.stamp_s, r.stats.w_avg, r.omega_radps);
  EXPECT_GT(detector.stats().starts, 10);
  // With map_at_start the vehicle also maps its first min_duration_s: at most one map more,
  // opened by the first scan.
  RunOptions at_start;
  at_start.divergence.map_at_start = true;
  const SimRun mapped = RunVehicle(world, at_start);
  const std::vector<double> starts = Starts(mapped);
  ASSERT_FALSE(starts.empty());
  EXPECT_EQ(starts.front(), mapped.scans.front().stamp_s);
  EXPECT_LE(mapped.divergence.starts, run.divergence.starts + 1);
}

// A zigzag through the unchanged hall: about 8 turns in place of 50 degrees or more, at
// 0.5 rad/s, in 200 s.
constexpr const char* kZigzag = R"(
map: livinglab.yaml
duration_s: 200
seed: 10
vehicles:
  - id: v
    scanner_mount: [0.3, 0.0, 0.0]
    route: [[6, 3], [14, 7], [22, 3], [30, 7], [38, 3], [46, 7], [54, 3]]
    loop: true
)";

TEST(DivergenceSimTest, TurningInAnUnchangedHallOpensNoMap) {
  const sim::World world = sim_testing::MakeWorld(kZigzag);
  const SimRun run = RunVehicle(world, DivergenceAlone());
  EXPECT_GT(run.divergence.rotating, 300);  // the turns happened, and were frozen
  EXPECT_LE(run.divergence.starts, 3);      // the defaults: a rare false map (see above)
  EXPECT_EQ(StartsAtTenPercent(run), 0);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
