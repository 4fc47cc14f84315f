#include "eval/global_localization.h"

#include <gtest/gtest.h>

#include "tests/sim/sim_test_util.h"

namespace fleetmap::eval {
namespace {

sim::World FleetShort() {
  auto world = sim::World::Load(sim::testing::LivingLabDir() + "fleet_short.yaml");
  EXPECT_TRUE(world.ok()) << world.status().ToString();
  return std::move(world).value();
}

// On the LivingLab hall, vehicles switched on without a pose are localized from their first
// scans; the figures say so.
TEST(GlobalLocalizationEvalTest, VehiclesOnTheHallFindThemselves) {
  const sim::World world = FleetShort();
  GlobalLocalizationOptions options;
  options.starts = 6;
  options.hold_s = 2.0;
  auto result = EvaluateGlobalLocalization(world, options);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  ASSERT_EQ(result->starts.size(), 6u);
  for (const GlobalStart& s : result->starts) {
    EXPECT_TRUE(s.localized) << "vehicle " << s.vehicle << " at " << s.start_s;
    EXPECT_LE(s.time_to_converge_s, options.drive_s);
    EXPECT_LT(s.final_error_m, options.tolerance_m);
  }
  EXPECT_EQ(result->starts[1].vehicle, 1u);  // spread over the vehicles
  EXPECT_DOUBLE_EQ(result->success_share(), 1.0);
  auto lines = GlobalLocalizationFigureLines(*result);
  ASSERT_TRUE(lines.ok());
  EXPECT_NE(lines->find("loc.global.success_share 1 ratio"), std::string::npos) << *lines;
  EXPECT_NE(lines->find("loc.global.time_to_converge_s "), std::string::npos) << *lines;
  EXPECT_NE(lines->find("loc.global.time_to_converge_s.max "), std::string::npos) << *lines;
}

// Vehicles sure of a pose 5 m from the truth find the map stops explaining their scans,
// search, and are right again within 15 s; with the lost check off they stay off.
TEST(GlobalLocalizationEvalTest, KidnappedVehiclesOnTheHallFindThemselvesAgain) {
  const sim::World world = FleetShort();
  GlobalLocalizationOptions options;
  options.kind = StartKind::kKidnapped;
  options.starts = 3;
  options.drive_s = 15.0;
  options.hold_s = 2.0;
  auto result = EvaluateGlobalLocalization(world, options);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  for (const GlobalStart& s : result->starts) {
    EXPECT_TRUE(s.localized) << "vehicle " << s.vehicle << " at " << s.start_s;
    EXPECT_LT(s.final_error_m, options.tolerance_m);
  }
  auto lines = GlobalLocalizationFigureLines(*result);
  ASSERT_TRUE(lines.ok());
  EXPECT_NE(lines->find("loc.kidnapped.success_share 1 ratio"), std::string::npos) << *lines;
  EXPECT_NE(lines->find("loc.kidnapped.time_to_recover_s.max "), std::string::npos) << *lines;

  options.localizer.lost_after_s = 0.0;  // never lost
  auto unaware = EvaluateGlobalLocalization(world, options);
  ASSERT_TRUE(unaware.ok()) << unaware.status().ToString();
  EXPECT_DOUBLE_EQ(unaware->success_share(), 0.0);
}

TEST(GlobalLocalizationEvalTest, NothingMeasuredIsAnErrorNotAScore) {
  EXPECT_FALSE(GlobalLocalizationFigureLines({}).ok());
  EXPECT_TRUE(std::isnan(GlobalLocalizationResult{}.success_share()));
  GlobalLocalizationOptions long_window;
  long_window.drive_s = 500.0;  // longer than the scenario
  EXPECT_EQ(EvaluateGlobalLocalization(FleetShort(), long_window).status().code(),
            core::StatusCode::kInvalidArgument);
  GlobalLocalizationOptions bad;
  bad.starts = 0;
  EXPECT_FALSE(bad.Validate().ok());
  // A start that never localized gives a share below 1 and no time for it.
  GlobalLocalizationResult one_failed;
  one_failed.starts.push_back({0, 5.0, true, 0.5, 0.01});
  one_failed.starts.push_back({1, 5.0, false, NAN, 12.0});
  EXPECT_DOUBLE_EQ(one_failed.success_share(), 0.5);
  auto lines = GlobalLocalizationFigureLines(one_failed);
  ASSERT_TRUE(lines.ok());
  EXPECT_NE(lines->find("loc.global.time_to_converge_s.max 0.5 s"), std::string::npos) << *lines;
}

}  // namespace
}  // namespace fleetmap::eval
