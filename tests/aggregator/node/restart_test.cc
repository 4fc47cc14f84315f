#include <gtest/gtest.h>

#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "aggregator/node/map_hash.h"
#include "auth/trailer.h"
#include "core/map/map_io.h"
#include "tests/aggregator/node/fleet_test_world.h"
#include "tests/aggregator/node/node_test_util.h"
#include "tests/aggregator/node/process_util.h"
#include "tests/aggregator/test_files.h"
#include "tests/support/multicast.h"
#include "vehicle_agent/tempmap_outbox.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::FleetMaps;

// Ports of this test only, so that parallel ctest runs never cross.
constexpr const char* kUplink = "udpm://239.255.76.121:7821?ttl=0";
constexpr const char* kDownlink = "udpm://239.255.76.122:7822?ttl=0";
// Each vehicle sends its next map this long after the last was sent (and not before it was
// answered), so that the kills fall while there is work: ~4 s for five maps.
constexpr double kMapSpacingS = 0.8;

// The current map after merging each vehicle's maps in its order, the vehicles interleaved
// as `order` says (the index of the vehicle whose next map comes).
std::string InMemoryFinalLine(const std::vector<std::vector<core::TempMap>>& fleet,
                              const std::vector<int>& order) {
  auto node = testing::MakeNode(nullptr);
  std::vector<size_t> next(fleet.size(), 0);
  double t = 1.0;
  for (int v : order) {
    const core::TempMap& map = fleet[v][next[v]++];
    testing::Feed(*node, map.vehicle_id, testing::TileMessages(map, lcmtypes::ToUtime(t)), t);
    t += 1.0;
  }
  return node->FinalLine();
}

TEST(AggregatorNodeRestartTest, TheFleetMapsGiveOneMapWhateverTheOrderAcrossVehicles) {
  const std::vector<std::vector<core::TempMap>> fleet = {FleetMaps("a"), FleetMaps("b")};
  const std::string interleaved = InMemoryFinalLine(fleet, {0, 1, 0, 1, 0, 1, 0, 1, 0, 1});
  EXPECT_NE(interleaved.find("version 10 "), std::string::npos) << interleaved;
  EXPECT_NE(interleaved.find("merged 10 rejected 0"), std::string::npos) << interleaved;
  EXPECT_EQ(InMemoryFinalLine(fleet, {0, 0, 0, 0, 0, 1, 1, 1, 1, 1}), interleaved);
  EXPECT_EQ(InMemoryFinalLine(fleet, {1, 1, 0, 1, 0, 0, 1, 1, 0, 0}), interleaved);
}

// One simulated vehicle: an outbox that gets the next map once the last is finished with.
struct Vehicle {
  std::string id;
  std::vector<core::TempMap> maps;
  size_t next = 0;
  double next_map_s = 0.0;  // a vehicle closes a temporary map every so often
  std::unique_ptr<vehicle_agent::TempMapOutbox> outbox;
  std::map<int32_t, int8_t> outcomes;  // the first final answer per sequence
};

class AckReceiver {
 public:
  AckReceiver(std::vector<Vehicle>* vehicles, std::mt19937* rng) : vehicles_(vehicles), rng_(rng) {}
  std::map<int, int> answers;  // acknowledgements seen per outcome
  bool pending_seen = false;   // a PENDING acknowledgement arrived
  void Handle(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    auto ack = lcmtypes::Decode<fleetmap::tempmap_ack_t>(
        rbuf->data, int(auth::PayloadSize(rbuf->data, rbuf->data_size)));
    ASSERT_TRUE(ack.ok()) << ack.status().ToString();
    if ((*rng_)() % 10 == 0) return;  // 10% of the acknowledgements are lost
    for (Vehicle& v : *vehicles_) {
      if (v.id != ack->vehicle_id) continue;
      const std::vector<int32_t> received(ack->received_tiles.begin(), ack->received_tiles.end());
      vehicle_agent::AckOutcome outcome = vehicle_agent::AckOutcome::kPending;
      if (ack->outcome == fleetmap::tempmap_ack_t::MERGED)
        outcome = vehicle_agent::AckOutcome::kMerged;
      if (ack->outcome == fleetmap::tempmap_ack_t::REJECTED)
        outcome = vehicle_agent::AckOutcome::kRejected;
      if (ack->outcome == fleetmap::tempmap_ack_t::DUPLICATE)
        outcome = vehicle_agent::AckOutcome::kDuplicate;
      if (outcome != vehicle_agent::AckOutcome::kPending)
        v.outcomes.emplace(ack->tempmap_seq, ack->outcome);
      ++answers[ack->outcome];
      if (ack->outcome == fleetmap::tempmap_ack_t::PENDING) pending_seen = true;
      v.outbox->OnAck(ack->tempmap_seq, received, outcome);
    }
  }

 private:
  std::vector<Vehicle>* vehicles_;
  std::mt19937* rng_;
};

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Two vehicles send five maps each over real multicast on loopback, losing 20% of their
// tiles and 10% of the acknowledgements, while the aggregator is killed (SIGKILL) at random
// moments and started again on its state folder.
TEST(AggregatorNodeRestartTest,
     KilledAndRestartedSeveralTimesTheAggregatorLosesNoMapAndMergesNoneTwice) {
  FLEETMAP_REQUIRE_MULTICAST(kUplink);
  FLEETMAP_REQUIRE_MULTICAST(kDownlink);
  fleetmap::testing::ScratchFolder folder;
  const std::string map_yaml = folder.File("hall.yaml");
  const std::string state = folder.File("state");
  ASSERT_TRUE(core::SaveMapServerMap(aggregator::testing::HallMap(), map_yaml).ok());

  std::vector<Vehicle> vehicles(2);
  vehicles[0].id = "a";
  vehicles[1].id = "b";
  for (Vehicle& v : vehicles) {
    v.maps = FleetMaps(v.id);
    vehicle_agent::OutboxOptions o;
    o.first_resend_s = 0.3;  // a restarted aggregator hears from the vehicles soon
    o.max_resend_s = 0.6;
    v.outbox = std::make_unique<vehicle_agent::TempMapOutbox>(o);
  }
  const std::string reference =
      InMemoryFinalLine({vehicles[0].maps, vehicles[1].maps}, {0, 1, 0, 1, 0, 1, 0, 1, 0, 1});

  const std::vector<std::string> args = {testing::AggregatorBinary(),
                                         "--map",
                                         map_yaml,
                                         "--state-dir",
                                         state,
                                         "--uplink-url",
                                         kUplink,
                                         "--downlink-url",
                                         kDownlink};
  const std::string out = folder.File("stdout"), err = folder.File("stderr");
  auto aggregator = std::make_unique<testing::Process>(args, out, err);
  const unsigned seed = std::random_device()();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  lcm::LCM uplink(kUplink), downlink(kDownlink);
  ASSERT_TRUE(uplink.good() && downlink.good());
  AckReceiver receiver(&vehicles, &rng);
  downlink.subscribe(lcmtypes::kTempMapAckChannel, &AckReceiver::Handle, &receiver);
  std::uniform_real_distribution<double> pause_s(0.1, 0.6);
  const double start = Now();
  double next_kill = start + pause_s(rng);
  int kills = 0, targeted_kills = 0;
  auto done = [&] {
    for (const Vehicle& v : vehicles)
      if (v.next < v.maps.size() || v.outbox->pending() > 0) return false;
    return true;
  };
  while (!done() && Now() - start < 40.0) {
    const double now = Now();
    for (Vehicle& v : vehicles) {
      if (v.outbox->pending() == 0 && v.next < v.maps.size() && now >= v.next_map_s) {
        ASSERT_TRUE(v.outbox->Add(v.maps[v.next++], now).ok());
        v.next_map_s = now + kMapSpacingS;
      }
      for (const core::TempMapTile& tile : v.outbox->Due(now)) {
        if (rng() % 5 == 0) continue;  // 20% of the tiles are lost on the way
        const auto bytes = testing::Encode(lcmtypes::ToMessage(tile, lcmtypes::ToUtime(now)));
        uplink.publish(lcmtypes::TempMapChannel(v.id), bytes.data(),
                       static_cast<unsigned>(bytes.size()));
      }
    }
    downlink.handleTimeout(5);
    // Kill -9 and start again: at random moments, and twice just after a PENDING
    // acknowledgement, when the tiles it names will never be sent again.
    const bool after_pending = receiver.pending_seen && targeted_kills < 2;
    receiver.pending_seen = false;
    if (after_pending || (kills < 4 && now >= next_kill)) {
      targeted_kills += after_pending;
      aggregator->Signal(SIGKILL);
      ASSERT_EQ(aggregator->Wait(10.0), 128 + SIGKILL);
      aggregator = std::make_unique<testing::Process>(args, out, err);
      ++kills;
      next_kill = Now() + pause_s(rng);
    }
  }
  ASSERT_TRUE(done()) << "maps still unacknowledged after 40 s; aggregator log:\n"
                      << testing::ReadText(err);
  EXPECT_GE(kills, 3);
  EXPECT_EQ(targeted_kills, 2);
  aggregator->Signal(SIGTERM);
  ASSERT_EQ(aggregator->Wait(20.0), 0) << testing::ReadText(err);
  const std::string final_line = testing::FinalLineOf(testing::ReadText(out));
  std::printf(
      "%d kills (%d after PENDING), %.1f s, acknowledgements: %d pending, %d merged, %d duplicate; "
      "%s\n",
      kills, targeted_kills, Now() - start, receiver.answers[fleetmap::tempmap_ack_t::PENDING],
      receiver.answers[fleetmap::tempmap_ack_t::MERGED],
      receiver.answers[fleetmap::tempmap_ack_t::DUPLICATE], final_line.c_str());

  // The same map as an uninterrupted run: nothing lost, nothing merged twice.
  const std::string expected_prefix = reference.substr(0, reference.find(" merged"));
  EXPECT_EQ(final_line.substr(0, final_line.find(" merged")), expected_prefix);
  auto restored = Aggregator::Open(aggregator::testing::HallMap(), AggregatorOptions{}, state);
  ASSERT_TRUE(restored.ok()) << restored.status().ToString();
  std::set<std::pair<std::string, int32_t>> merged;
  for (const MergeCommit& c : restored->store().provenance().commits())
    EXPECT_TRUE(merged.insert({c.source.vehicle_id, c.source.tempmap_sequence}).second)
        << c.source.vehicle_id << "#" << c.source.tempmap_sequence << " merged twice";
  EXPECT_EQ(restored->store().version(), 10u);
  for (const Vehicle& v : vehicles) {
    for (const core::TempMap& m : v.maps) {
      auto it = v.outcomes.find(m.sequence);
      ASSERT_NE(it, v.outcomes.end()) << v.id << "#" << m.sequence << " never answered";
      EXPECT_NE(it->second, fleetmap::tempmap_ack_t::REJECTED);
      EXPECT_TRUE(merged.count({v.id, m.sequence})) << v.id << "#" << m.sequence << " lost";
    }
  }
}

}  // namespace
}  // namespace fleetmap::aggregator::node
