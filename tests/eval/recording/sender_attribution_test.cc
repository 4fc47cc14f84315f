// Whose word counts in a recorded run: traffic on the fleet's channels that its owner did not
// send (or, with the fleet key, did not sign) is refused by reason and changes no figure; a
// log in which nothing can be attributed is an error.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>
#include <vector>

#include "auth/signer.h"
#include "eval/recording/recorded_run.h"
#include "lcmtypes/convert.h"
#include "tests/eval/recording/recorded_run_fixture.h"

namespace fleetmap::eval::recording {
namespace {

using testing::RecordedRunTest;

// Traffic that is not the aggregator's (or the vehicle's) on the fleet's channels is left out:
// the run scores exactly as without it, and each refusal is counted by its reason.
TEST_F(RecordedRunTest, ForeignTrafficOnTheFleetsChannelsChangesNoFigure) {
  auto read = [&](bool foreign) {
    signers_.clear();
    {
      lcm::LogFile log(path_, "w");
      WriteMergeRun(log);
      if (foreign) WriteForeignTraffic(log);
    }
    return ReadRecordedRun({path_}, *world_, Options());
  };
  auto clean = read(false);
  auto mixed = read(true);
  ASSERT_TRUE(clean.ok()) << clean.status().ToString();
  ASSERT_TRUE(mixed.ok()) << mixed.status().ToString();

  ASSERT_EQ(mixed->run.merges.size(), 1u);
  EXPECT_TRUE(mixed->run.merges[0].accepted);
  EXPECT_EQ(mixed->run.final_map.state({100, 60}), core::CellState::kOccupied);
  EXPECT_EQ(mixed->run.final_map.cells(), clean->run.final_map.cells());
  std::map<std::string, std::string> clean_figures, mixed_figures;
  for (const auto& [k, v] : FleetJsonPairs(clean->fleet)) clean_figures[k] = v;
  for (const auto& [k, v] : FleetJsonPairs(mixed->fleet))
    if (k.rfind("fleet.messages_refused", 0) != 0) mixed_figures[k] = v;
  EXPECT_EQ(clean_figures.at("fleet.messages_refused"), "0");
  clean_figures.erase("fleet.messages_refused");
  EXPECT_EQ(mixed_figures, clean_figures);
  EXPECT_EQ(mixed->fleet.messages_refused,
            (std::map<std::string, int>{{"unnamed", 3}, {"wrong_sender", 2}, {"replayed", 1}}));
  EXPECT_NE(FleetFigureLines(mixed->fleet).find("fleet.messages_refused 6 count"),
            std::string::npos);
}

// With the fleet key, a message counts only if its MAC is right: the name alone (an identity
// trailer) or another fleet's key is refused; read with a wrong key, nothing can be scored.
TEST_F(RecordedRunTest, WithTheFleetKeyOnlyWhatItsMacVerifiesIsRead) {
  key_ = auth::GenerateKey();
  {
    lcm::LogFile log(path_, "w");
    WriteMergeRun(log);
    std::vector<uint8_t> named = Encode(Report(core::Pose2(), false, 0));
    auth::Signer(std::nullopt, "aggregator", 1u << 20).Seal(lcmtypes::kMergeReportChannel, named);
    LogBytes(log, 10.25, lcmtypes::kMergeReportChannel, named);
    std::vector<uint8_t> forged = Encode(Report(core::Pose2(), false, 0));
    auth::Signer(auth::GenerateKey(), "aggregator", 1u << 21)
        .Seal(lcmtypes::kMergeReportChannel, forged);
    LogBytes(log, 10.26, lcmtypes::kMergeReportChannel, forged);
  }
  RecordedRunOptions options = Options();
  options.fleet_key = key_;
  auto run = ReadRecordedRun({path_}, *world_, options);
  ASSERT_TRUE(run.ok()) << run.status().ToString();
  ASSERT_EQ(run->run.merges.size(), 1u);
  EXPECT_TRUE(run->run.merges[0].accepted);
  EXPECT_EQ(run->fleet.messages_refused,
            (std::map<std::string, int>{{"forged", 1}, {"unsigned", 1}}));

  options.fleet_key = auth::GenerateKey();
  auto wrong_key = ReadRecordedRun({path_}, *world_, options);
  ASSERT_FALSE(wrong_key.ok());
  EXPECT_EQ(wrong_key.status().code(), core::StatusCode::kFailedPrecondition);
  EXPECT_NE(wrong_key.status().ToString().find("key"), std::string::npos);
}

// A log of processes that name no sender (or of another system on the same channels) has
// nothing the evaluation may believe: an error, never a run scored over nothing.
TEST_F(RecordedRunTest, ALogWhereNoMessageNamesItsSenderIsAnError) {
  {
    lcm::LogFile log(path_, "w");
    LogBytes(log, 5.0, lcmtypes::kMergeReportChannel, Encode(Report(core::Pose2(), true, 1)));
    LogBytes(log, 5.5, lcmtypes::PoseChannel("alpha"), Encode(Pose("alpha", 1.5, 0)));
  }
  auto run = ReadRecordedRun({path_}, *world_, Options());
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.status().code(), core::StatusCode::kFailedPrecondition);
  EXPECT_NE(run.status().ToString().find("2 messages"), std::string::npos)
      << run.status().ToString();
}

}  // namespace
}  // namespace fleetmap::eval::recording
