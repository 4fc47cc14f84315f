// The node's bad-input handling: each bad message counted, each cause logged once.
#include "vehicle_agent/node/message_checks.h"

#include <gtest/gtest.h>

#include "lcmtypes/convert.h"
#include "vehicle_agent/node/agent_messages.h"

namespace fleetmap::vehicle_agent::node {
namespace {

class MessageChecksTest : public ::testing::Test {
 protected:
  MessageChecksTest()
      : log_([this](LogLevel, const std::string& line) { lines_.push_back(line); }),
        checks_("v1", &log_, &counters_) {}

  std::vector<std::string> lines_;
  CauseLog log_;
  AgentNodeCounters counters_;
  MessageChecks checks_;
};

TEST_F(MessageChecksTest, DecodesGoodMessagesAndCountsEveryBadOneButLogsItsCauseOnce) {
  const core::OdometrySample odom{2.5, core::Pose2(1.0, 2.0, 0.5), 0.3, 0.1};
  const std::vector<uint8_t> bytes = Encode(lcmtypes::ToMessage(odom, "v1"));
  auto good =
      checks_.Decode<fleetmap::odometry_t>("ODOM_v1", bytes.data(), static_cast<int>(bytes.size()));
  ASSERT_TRUE(good.has_value());
  EXPECT_EQ(good->vehicle_id, "v1");
  EXPECT_EQ(counters_.malformed_messages, 0);
  EXPECT_TRUE(lines_.empty());

  for (int i = 0; i < 3; ++i) {
    EXPECT_FALSE(checks_.Decode<fleetmap::odometry_t>("ODOM_v1", bytes.data(),
                                                      static_cast<int>(bytes.size()) / 2));
  }
  EXPECT_EQ(counters_.malformed_messages, 3);
  ASSERT_EQ(lines_.size(), 1u);
  EXPECT_NE(lines_[0].find("ODOM_v1: bad message dropped"), std::string::npos) << lines_[0];

  // Another channel is another cause.
  checks_.Malformed("scanner", core::InvalidArgument("scan has no beams"));
  EXPECT_EQ(counters_.malformed_messages, 4);
  ASSERT_EQ(lines_.size(), 2u);
  EXPECT_NE(lines_[1].find("scan has no beams"), std::string::npos) << lines_[1];
  EXPECT_EQ(counters_.wrong_vehicle, 0);
}

TEST_F(MessageChecksTest, MessagesNamingAnotherVehicleAreCountedAndTheirIdCutShortInTheLog) {
  EXPECT_TRUE(checks_.OurVehicle("SCAN_v1", "v1"));
  EXPECT_EQ(counters_.wrong_vehicle, 0);
  EXPECT_FALSE(checks_.OurVehicle("SCAN_v1", std::string(500, 'x')));
  EXPECT_FALSE(checks_.OurVehicle("SCAN_v1", "v2"));
  EXPECT_FALSE(checks_.OurVehicle("SCAN_v1", "v1 "));
  EXPECT_EQ(counters_.wrong_vehicle, 3);
  EXPECT_EQ(counters_.malformed_messages, 0);
  ASSERT_EQ(lines_.size(), 1u);  // one cause
  EXPECT_NE(lines_[0].find("'" + std::string(64, 'x') + "'"), std::string::npos) << lines_[0];
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
