// The generated LCM types through lcm::LCM in process (memq://): a typed subscription, and
// a raw one that survives a message whose decode() throws.
//
// Handlers are objects subscribed with subscribeFunction() and the object as context, not
// with subscribe(&Class::Method, object): LCM 1.3.1 calls the latter through a pointer to
// member, which GCC 12 miscompiles under -fsanitize=vptr (part of FLEETMAP_SANITIZE's
// -fsanitize=undefined): the handler runs with this == nullptr and crashes.

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/lcmtypes/lcm_expect_same.h"
#include "tests/lcmtypes/lcm_samples.h"

namespace fleetmap {
namespace {

using lcmtypes::testing::Bytes;
using lcmtypes::testing::Encode;
using lcmtypes::testing::ExpectSame;
using lcmtypes::testing::MakeSample;

class ScanHandler {
 public:
  static void Dispatch(const lcm::ReceiveBuffer* /*rbuf*/, const std::string& channel,
                       const laser_scan_t* msg, ScanHandler* handler) {
    handler->OnScan(channel, *msg);
  }
  void OnScan(const std::string& channel, const laser_scan_t& msg) {
    channels.push_back(channel);
    scans.push_back(msg);
  }
  std::vector<std::string> channels;
  std::vector<laser_scan_t> scans;
};

TEST(LcmTypesTest, MemqPublishSubscribeRoundTrip) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  ScanHandler handler;
  ASSERT_NE(lcm.subscribeFunction("SCAN_.*", &ScanHandler::Dispatch, &handler), nullptr);
  const laser_scan_t sent = MakeSample<laser_scan_t>();
  ASSERT_EQ(lcm.publish("SCAN_agv_1", &sent), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  ASSERT_EQ(handler.scans.size(), 1u);
  EXPECT_EQ(handler.channels[0], "SCAN_agv_1");
  ExpectSame(sent, handler.scans[0]);
}

// A typed subscription decodes inside LCM's C callback: a decode() that throws escapes
// handleTimeout() and leaves the instance unusable (the next handle asserts `!lcm->in_handle`
// in lcm.c and aborts). Outside data must therefore be subscribed raw and decoded by the
// handler, catching exceptions.
class RawScanHandler {
 public:
  static void Dispatch(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/,
                       RawScanHandler* handler) {
    handler->OnRaw(*rbuf);
  }
  void OnRaw(const lcm::ReceiveBuffer& rbuf) {
    laser_scan_t msg;
    try {
      if (msg.decode(rbuf.data, 0, static_cast<int>(rbuf.data_size)) < 0) {
        ++rejected;
        return;
      }
    } catch (const std::exception&) {
      ++rejected;
      return;
    }
    scans.push_back(msg);
  }
  int rejected = 0;
  std::vector<laser_scan_t> scans;
};

TEST(LcmTypesTest, RawSubscriptionSurvivesMalformedMessage) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  RawScanHandler handler;
  ASSERT_NE(lcm.subscribeFunction("SCAN_.*", &RawScanHandler::Dispatch, &handler), nullptr);
  Bytes bad = Encode(MakeSample<laser_scan_t>());
  bad[16] = bad[17] = bad[18] = bad[19] = 0;  // vehicle_id length 0: decode() throws
  ASSERT_EQ(lcm.publish("SCAN_agv_1", bad.data(), static_cast<unsigned>(bad.size())), 0);
  const laser_scan_t good = MakeSample<laser_scan_t>();
  ASSERT_EQ(lcm.publish("SCAN_agv_1", &good), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  EXPECT_EQ(handler.rejected, 1);
  ASSERT_EQ(handler.scans.size(), 1u);
  ExpectSame(good, handler.scans[0]);
}

}  // namespace
}  // namespace fleetmap
