#include "sim/lcm_bridge/sim_publisher.h"

#include <gtest/gtest.h>

#include <map>

#include "lcmtypes/convert.h"
#include "tests/sim/sim_test_util.h"

namespace fleetmap::sim::lcm_bridge {
namespace {

constexpr const char* kScenario = R"(
map: room.yaml
duration_s: 2
vehicles:
  - {id: alpha, route: [[1, 3], [4, 3]], external_pose: {rate_hz: 5}}
  - {id: beta, scanner: TiM571, route: [[1, 2], [4, 2]]}
)";

// Counts messages per channel and checks that each decodes and validates.
class Recorder {
 public:
  void OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    ++count[channel];
    bool ok = true;
    if (channel.rfind("SCAN_", 0) == 0) {
      auto m = lcmtypes::Decode<fleetmap::laser_scan_t>(rbuf->data, int(rbuf->data_size));
      ok = m.ok() && lcmtypes::FromMessage(*m).ok();
      if (ok) last_scan_beams[channel] = m->num_ranges;
    } else if (channel.rfind("ODOM_", 0) == 0) {
      auto m = lcmtypes::Decode<fleetmap::odometry_t>(rbuf->data, int(rbuf->data_size));
      ok = m.ok() && lcmtypes::FromMessage(*m).ok();
    } else {
      auto m = lcmtypes::Decode<fleetmap::pose_with_covariance_t>(rbuf->data, int(rbuf->data_size));
      ok = m.ok() && lcmtypes::FromMessage(*m).ok();
    }
    invalid += !ok;
  }
  std::map<std::string, int> count;
  std::map<std::string, int> last_scan_beams;
  int invalid = 0;
};

TEST(SimPublisherTest, PublishesEveryVehiclesChannelsOverMemq) {
  const sim::World world =
      sim::World::Create(sim::ParseScenario(kScenario, "s.yaml").value(), sim::testing::Room())
          .value();
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Recorder recorder;
  lcm.subscribe(".*", &Recorder::OnMessage, &recorder);
  sim::Simulator simulator(&world);
  SimPublisher publisher(&lcm, &world, {1000.0, true});
  while (auto e = simulator.Next()) {
    publisher.Publish(*e);
    while (lcm.handleTimeout(0) > 0) {
    }
  }
  EXPECT_EQ(recorder.invalid, 0);
  EXPECT_NEAR(recorder.count["SCAN_alpha"], 50, 1);  // S300, 25 Hz, 2 s
  EXPECT_NEAR(recorder.count["SCAN_beta"], 30, 1);   // TiM571, 15 Hz
  EXPECT_EQ(recorder.count["TRUTH_alpha"], recorder.count["SCAN_alpha"]);
  EXPECT_NEAR(recorder.count["ODOM_beta"], 100, 1);
  EXPECT_NEAR(recorder.count["EXTPOSE_alpha"], 10, 1);
  EXPECT_EQ(recorder.count.count("EXTPOSE_beta"), 0u);
  EXPECT_EQ(recorder.last_scan_beams["SCAN_beta"], 811);
  EXPECT_EQ(publisher.counters().failures, 0);
}

}  // namespace
}  // namespace fleetmap::sim::lcm_bridge
