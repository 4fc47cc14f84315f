// Where the filter's first pose comes from (a kept pose, the first external pose) and the pose
// kept for the next start.
#include "vehicle_agent/node/pose_start.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/scratch_folder.h"
#include "vehicle_agent/localization/particle_set.h"

namespace fleetmap::vehicle_agent::node {
namespace {

class PoseStartTest : public ::testing::Test {
 protected:
  PoseStartTest() : log_([this](LogLevel, const std::string& l) { lines_.push_back(l); }) {
    options_.pipeline.vehicle_id = "v1";
    options_.outbox.state_dir = dir_.path();
    options_.initial_pose = InitialPoseSource::kGiven;
    options_.last_pose.period_s = 2.0;
  }
  // After the options are set.
  PoseStart& Start() {
    pipeline_ = std::make_unique<AgentPipeline>(options_.pipeline);
    start_ = std::make_unique<PoseStart>(options_, pipeline_.get(), &log_, &checks_, &counters_);
    return *start_;
  }
  core::Pose2 FilterMean() const { return ComputeMoments(pipeline_->localizer().particles()).mean; }
  bool Logged(const std::string& text) const {
    for (const std::string& l : lines_)
      if (l.find(text) != std::string::npos) return true;
    return false;
  }
  static AgentStep Step(const core::Pose2& pose, bool well_localized = true) {
    AgentStep step;
    step.pose.pose_in_map = pose;
    step.pose.map_version = 3;
    step.well_localized = well_localized;
    return step;
  }

  fleetmap::testing::ScratchFolder dir_;
  std::vector<std::string> lines_;
  CauseLog log_;
  AgentNodeCounters counters_;
  MessageChecks checks_{"v1", &log_, &counters_};
  AgentNodeOptions options_;
  std::unique_ptr<AgentPipeline> pipeline_;
  std::unique_ptr<PoseStart> start_;
};

TEST_F(PoseStartTest, AKeptPoseIsUsedWhenTheFirstOdometrySampleSaysTheVehicleHasNotMoved) {
  ASSERT_TRUE(
      PoseStore(dir_.path()).Store({core::Pose2(3.0, 2.0, 0.5), core::Pose2(10, -4, 1), 4}).ok());
  PoseStart& start = Start();
  start.LoadKept();
  start.OnFirstMap();
  EXPECT_FALSE(start.initialized());  // waits for the odometry
  start.OnOdometry(core::Pose2(10.005, -4.0, 1.0));
  EXPECT_TRUE(start.initialized());
  EXPECT_EQ(counters_.starts_from_last_pose, 1);
  EXPECT_NEAR(FilterMean().x_m, 3.0, 0.05);
  EXPECT_NEAR(FilterMean().y_m, 2.0, 0.05);
  EXPECT_TRUE(Logged("starting from the last pose kept in " + dir_.path() + "/last_pose"));
}

TEST_F(PoseStartTest, AKeptPoseIsLeftWhenTheVehicleMovedSince) {
  ASSERT_TRUE(
      PoseStore(dir_.path()).Store({core::Pose2(3.0, 2.0, 0.5), core::Pose2(10, -4, 1), 4}).ok());
  PoseStart& start = Start();
  start.LoadKept();
  start.OnFirstMap();
  start.OnOdometry(core::Pose2(11.0, -4.0, 1.0));
  EXPECT_TRUE(start.initialized());  // from the given pose, which the first map set
  EXPECT_EQ(counters_.starts_from_last_pose, 0);
  EXPECT_TRUE(
      Logged("last pose not used: the odometry moved 1.00 m, 0.000 rad since it was kept; "
             "starting from the given pose"));
  EXPECT_FALSE(pipeline_->localizer().initialized());  // nothing was started here
}

TEST_F(PoseStartTest, WithoutAKeptPoseTheFirstMapStartsTheFilter) {
  PoseStart& start = Start();
  start.LoadKept();  // none in the folder
  EXPECT_FALSE(start.initialized());
  start.OnFirstMap();
  EXPECT_TRUE(start.initialized());
  EXPECT_TRUE(lines_.empty());
}

TEST_F(PoseStartTest, UnderFirstExternalTheFirstExternalPoseStartsTheFilterEvenBeforeTheMap) {
  ASSERT_TRUE(PoseStore(dir_.path()).Store({core::Pose2(3.0, 2.0, 0.5), core::Pose2(), 4}).ok());
  options_.initial_pose = InitialPoseSource::kFirstExternal;
  options_.use_external_pose = true;
  PoseStart& start = Start();
  start.LoadKept();  // not read: the external pose comes first
  core::PoseEstimate bad;
  bad.pose_in_map = core::Pose2(NAN, 1.0, 0.0);
  core::PoseEstimate pose;
  pose.pose_in_map = core::Pose2(6.0, 1.5, -0.3);
  start.OnExternalPose(pose);  // before the map: held
  EXPECT_FALSE(start.initialized());
  start.OnFirstMap();
  EXPECT_TRUE(start.initialized());
  EXPECT_NEAR(FilterMean().x_m, 6.0, 0.2);
  EXPECT_TRUE(Logged("initial pose from the external localization"));
  start.OnOdometry(core::Pose2());  // the kept pose was never read: nothing to decide
  EXPECT_EQ(counters_.starts_from_last_pose, 0);

  // A pose that cannot start the filter is a bad message.
  PoseStart& again = Start();
  again.OnFirstMap();
  again.OnExternalPose(bad);
  EXPECT_FALSE(again.initialized());
  EXPECT_EQ(counters_.malformed_messages, 1);
  again.OnExternalPose(pose);
  EXPECT_TRUE(again.initialized());
}

TEST_F(PoseStartTest, KeepsTheWellLocalizedPoseOfAMovingVehicleOncePerPeriodAndAtExit) {
  PoseStart& start = Start();
  const PoseStore& store = start.store();
  start.OnStep(Step(core::Pose2(1, 1, 0)), 0.0);  // no odometry yet: nothing to compare later
  EXPECT_EQ(store.Load().status().code(), core::StatusCode::kNotFound);

  start.OnOdometry(core::Pose2(0, 0, 0));
  start.OnStep(Step(core::Pose2(1, 1, 0)), 0.0);
  ASSERT_TRUE(store.Load().ok());
  EXPECT_DOUBLE_EQ(store.Load()->base_in_map.x_m, 1.0);
  EXPECT_EQ(store.Load()->map_version, 3);

  start.OnOdometry(core::Pose2(1, 0, 0));
  start.OnStep(Step(core::Pose2(2, 1, 0)), 1.0);  // within the period
  EXPECT_DOUBLE_EQ(store.Load()->base_in_map.x_m, 1.0);
  start.OnStep(Step(core::Pose2(2, 1, 0), /*well_localized=*/false), 2.5);  // not worth it
  EXPECT_DOUBLE_EQ(store.Load()->base_in_map.x_m, 1.0);
  start.OnStep(Step(core::Pose2(2, 1, 0)), 2.5);
  EXPECT_DOUBLE_EQ(store.Load()->base_in_map.x_m, 2.0);
  EXPECT_DOUBLE_EQ(store.Load()->odometry.x_m, 1.0);

  start.OnStep(Step(core::Pose2(2.5, 1, 0)), 5.0);  // the odometry has not moved since
  EXPECT_DOUBLE_EQ(store.Load()->base_in_map.x_m, 2.0);
  start.OnOdometry(core::Pose2(2, 0, 0));
  start.KeepLast(5.1);  // at exit: whatever the period
  EXPECT_DOUBLE_EQ(store.Load()->base_in_map.x_m, 2.5);
  EXPECT_DOUBLE_EQ(store.Load()->odometry.x_m, 2.0);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
