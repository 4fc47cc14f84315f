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

// 1000 B/s with 2000 B at once: two 1500-byte messages go (the second into debt), then
// nothing until the debt is paid back: 1500 B per 1.5 s, the budget.
TEST(SendPacerTest, TheByteBudgetHoldsWhateverTheMessagesSize) {
  SendPacer pacer({1000.0, 100.0, 1000.0, 2000.0});
  EXPECT_DOUBLE_EQ(pacer.BytesAllowed(0.0), 2000.0);
  ASSERT_TRUE(pacer.MaySend(0.0));
  pacer.Sent(1, 1500);
  ASSERT_TRUE(pacer.MaySend(0.0));
  pacer.Sent(1, 1500);
  EXPECT_FALSE(pacer.MaySend(0.0));
  EXPECT_FALSE(pacer.MaySend(0.9)) << "1000 B in debt until 1 s";
  EXPECT_DOUBLE_EQ(pacer.BytesAllowed(1.5), 500.0);
  ASSERT_TRUE(pacer.MaySend(1.5));
  pacer.Sent(1, 1500);
  EXPECT_FALSE(pacer.MaySend(2.4)) << "1000 B in debt again until 2.5 s";
  EXPECT_TRUE(pacer.MaySend(2.6));
  EXPECT_DOUBLE_EQ(pacer.BytesAllowed(100.0), 2000.0) << "never more than the burst";
  EXPECT_GT(SendPacer(PacerOptions{}).BytesAllowed(0.0), 1e12) << "no byte budget";
}

TEST(SendPacerTest, BadOptionsAreRefused) {
  EXPECT_FALSE((PacerOptions{10.0, 4.0, -1.0}).Validate().ok());
  EXPECT_FALSE((PacerOptions{10.0, 4.0, 100.0, 0.0}).Validate().ok());
  EXPECT_FALSE((PacerOptions{0.0, 4.0}).Validate().ok());
  EXPECT_FALSE((PacerOptions{10.0, 0.5}).Validate().ok());
  EXPECT_TRUE(PacerOptions{}.Validate().ok());
}

}  // namespace
}  // namespace fleetmap::core
