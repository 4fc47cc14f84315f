#include "core/codec/send_pacer.h"

#include <gtest/gtest.h>

namespace fleetmap::core {
namespace {

TEST(SendPacerTest, ABurstGoesAtOnceThenTheRateHolds) {
  SendPacer pacer({100.0, 10.0});
  EXPECT_EQ(pacer.Allowed(0.0), 10);
  pacer.Sent(10);
  EXPECT_EQ(pacer.Allowed(0.0), 0);
  EXPECT_EQ(pacer.Allowed(0.05), 5);  // 100 per second
  pacer.Sent(5);
  EXPECT_EQ(pacer.Allowed(10.0), 10);  // never more than the burst
}

TEST(SendPacerTest, TimeGoingBackwardsGivesNothingExtra) {
  SendPacer pacer({100.0, 4.0});
  pacer.Allowed(5.0);
  pacer.Sent(4);
  EXPECT_EQ(pacer.Allowed(4.0), 0);
  EXPECT_EQ(pacer.Allowed(5.02), 2);
}

TEST(SendPacerTest, BadOptionsAreRefused) {
  EXPECT_FALSE((PacerOptions{0.0, 4.0}).Validate().ok());
  EXPECT_FALSE((PacerOptions{10.0, 0.5}).Validate().ok());
  EXPECT_TRUE(PacerOptions{}.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::core
