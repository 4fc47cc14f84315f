// The start sequence's requests, in the order SICK's driver sends them (docs/drivers.md).
#include "drivers/sick/start_sequence.h"

#include <gtest/gtest.h>

namespace fleetmap::drivers::sick {
namespace {

TEST(StartSequenceTest, LoginStartRunThenSubscribe) {
  StartSequenceOptions o;
  o.protocol = ColaProtocol::kColaA;
  EXPECT_EQ(StartRequests(o),
            (std::vector<std::string>{"sMN SetAccessMode 3 F4724744", "sMN LMCstartmeas", "sMN Run",
                                      "sEN LMDscandata 1"}));
}

TEST(StartSequenceTest, PollingSubscribesToNothingAndEachStepCanBeLeftOut) {
  StartSequenceOptions o;
  o.protocol = ColaProtocol::kColaA;
  o.streaming = false;
  EXPECT_EQ(StartRequests(o), (std::vector<std::string>{"sMN SetAccessMode 3 F4724744",
                                                        "sMN LMCstartmeas", "sMN Run"}));
  o.login = false;
  o.start_measurement = false;
  EXPECT_TRUE(StartRequests(o).empty());
}

}  // namespace
}  // namespace fleetmap::drivers::sick
