// fleetmap-agent killed with SIGKILL while its temporary maps are unacknowledged (no
// aggregator yet), started again on the same state folder: it sends them again and an
// aggregator merges them. Killed again after the merges but before it heard of them, it
// sends them once more and they are answered DUPLICATE, not merged twice; a start after that
// sends nothing. Real LCM multicast on loopback; both programs as processes.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>
#include <thread>

#include "aggregator/aggregator.h"
#include "auth/trailer.h"
#include "core/map/map_io.h"
#include "fleetmap/tempmap_ack_t.hpp"
#include "tests/support/multicast.h"
#include "tests/support/process.h"
#include "tests/support/scratch_folder.h"
#include "tests/vehicle_agent/node/node_test_util.h"
#include "tests/vehicle_agent/node/sensor_feed.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using fleetmap::testing::Process;
using fleetmap::testing::ReadText;

// Group and ports of this test only (other tests use other ones).
std::string Url(int group, int port) {
  return "udpm://239.255.77." + std::to_string(group) + ":" + std::to_string(port) +
         "?ttl=0&recv_buf_size=8388608";
}

// Every message of type T heard on the channels it is subscribed to, decoded.
template <typename T>
struct Heard {
  void On(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    auto m = lcmtypes::Decode<T>(rbuf->data,
                                 static_cast<int>(auth::PayloadSize(rbuf->data, rbuf->data_size)));
    ASSERT_TRUE(m.ok()) << channel;
    messages.push_back(std::move(m).value());
  }
  std::vector<T> messages;
};

// The sequences of the tiles heard from index `from` on.
std::set<int32_t> TileSequences(const Heard<fleetmap::tempmap_tile_t>& tiles, size_t from = 0) {
  std::set<int32_t> out;
  for (size_t i = from; i < tiles.messages.size(); ++i) out.insert(tiles.messages[i].tempmap_seq);
  return out;
}

// v1's final acknowledgements (not PENDING) from index `from` on: outcomes by sequence, in the
// order they came.
std::map<int32_t, std::vector<int8_t>> FinalAcks(const Heard<fleetmap::tempmap_ack_t>& acks,
                                                 size_t from = 0) {
  std::map<int32_t, std::vector<int8_t>> out;
  for (size_t i = from; i < acks.messages.size(); ++i) {
    const fleetmap::tempmap_ack_t& a = acks.messages[i];
    if (a.vehicle_id == "v1" && a.outcome != fleetmap::tempmap_ack_t::PENDING)
      out[a.tempmap_seq].push_back(a.outcome);
  }
  return out;
}

int64_t CounterOf(const fleetmap::status_t& s, const std::string& name) {
  for (int i = 0; i < s.num_counters; ++i)
    if (s.counter_names[i] == name) return s.counter_values[i];
  return -1;
}

// The sequence numbers of the temporary maps kept in `state_dir`.
std::set<int32_t> PendingFiles(const std::string& state_dir) {
  std::set<int32_t> out;
  for (const auto& e : std::filesystem::directory_iterator(state_dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("tempmap_", 0) == 0 && e.path().extension() == ".fmtm")
      out.insert(std::stoi(name.substr(8)));
  }
  return out;
}

class AgentKillTest : public ::testing::Test {
 protected:
  // 50 for the kill test, 60 for the stop test: groups 239.255.77.51-54 or .61-64, ports to match.
  static int TestBase() {
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    return name.rfind("Stopped", 0) == 0 ? 60 : 50;
  }

  void SetUp() override {
    FLEETMAP_REQUIRE_MULTICAST(sensor_);
    ASSERT_TRUE(core::SaveMapServerMap(world_.static_map(), dir_.File("room.yaml")).ok());
    ASSERT_TRUE(sensor_lcm_.good() && uplink_lcm_.good() && downlink_lcm_.good());
    uplink_lcm_.subscribe("TEMPMAP_v1", &Heard<fleetmap::tempmap_tile_t>::On, &tiles_);
    uplink_lcm_.subscribe("STATUS_agent_v1", &Heard<fleetmap::status_t>::On, &agent_status_);
    downlink_lcm_.subscribe("TEMPMAP_ACK", &Heard<fleetmap::tempmap_ack_t>::On, &acks_);
    downlink_lcm_.subscribe("STATUS_aggregator", &Heard<fleetmap::status_t>::On,
                            &aggregator_status_);
  }

  // The agent on the test's state folder; `downlink` is where it listens for acknowledgements.
  std::unique_ptr<Process> StartAgent(const std::string& downlink) {
    const core::Pose2 start = world_.VehicleStateAt(0, 0.0).pose;
    auto agent = std::make_unique<Process>(
        std::vector<std::string>{FLEETMAP_AGENT_BINARY, "--vehicle-id", "v1", "--map",
                                 dir_.File("room.yaml"), "--initial-pose",
                                 std::to_string(start.x_m) + "," + std::to_string(start.y_m) + "," +
                                     std::to_string(start.theta_rad),
                                 "--scanner-mount", "0.3,0,0", "--sensor-url", sensor_,
                                 "--uplink-url", uplink_, "--downlink-url", downlink, "--state-dir",
                                 state_dir()},
        dir_.File("agent_out.txt"), dir_.File("agent_err.txt"));
    EXPECT_TRUE(agent->started());
    return agent;
  }

  // Handles what arrives until `done` or the deadline (against a hang only). Returns done().
  template <typename Done>
  bool Listen(double deadline_s, Done done) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(deadline_s);
    while (!done() && std::chrono::steady_clock::now() < end) {
      uplink_lcm_.handleTimeout(10);
      while (downlink_lcm_.handleTimeout(0) > 0) {
      }
    }
    return done();
  }

  // A started agent's first heartbeat (sent after its first round of tiles).
  bool FirstAgentStatus() {
    return Listen(20.0, [&] { return !agent_status_.messages.empty(); });
  }

  // Kills the agent with SIGKILL; what it sent before is handled, its heartbeats forgotten.
  void Kill(std::unique_ptr<Process>& agent) {
    agent->Signal(SIGKILL);
    ASSERT_EQ(agent->Wait(10.0), 128 + SIGKILL);
    agent.reset();
    while (uplink_lcm_.handleTimeout(100) > 0) {
    }
    agent_status_.messages.clear();
  }

  // Publishes the world's odometry and scans at 4x real time; returns the number of scans.
  int64_t Drive() {
    return static_cast<int64_t>(testing::PublishSensors(sensor_lcm_, world_, 4.0, [&] {
                                  while (uplink_lcm_.handleTimeout(0) > 0) {
                                  }
                                }).size());
  }

  // Waits until the agent's heartbeat counts every one of `scans` as handled.
  bool EveryScanHandled(int64_t scans) {
    return Listen(30.0, [&] {
      const fleetmap::status_t& s = agent_status_.messages.back();
      return CounterOf(s, "scans") + CounterOf(s, "scans_skipped") +
                 CounterOf(s, "scans_waiting_for_map") ==
             scans;
    });
  }

  std::vector<std::string> AggregatorArgs() const {
    return {FLEETMAP_AGGREGATOR_BINARY,
            "--map",
            dir_.File("room.yaml"),
            "--state-dir",
            dir_.File("aggregator_state"),
            "--uplink-url",
            uplink_,
            "--downlink-url",
            downlink_};
  }

  std::string state_dir() const { return dir_.File("agent_state"); }
  std::string Logs() const {
    return "agent:\n" + ReadText(dir_.File("agent_err.txt")) + "aggregator:\n" +
           ReadText(dir_.File("aggregator_err.txt"));
  }

  const sim::World world_ = testing::RoomWorld(testing::kPallet);
  fleetmap::testing::ScratchFolder dir_;
  // Groups and ports of each test of its own: ctest runs them at the same time, and two agents
  // "v1" on one group would answer each other's maps.
  const int base_ = TestBase();
  const std::string sensor_ = Url(base_ + 1, 7900 + base_ + 1);
  const std::string uplink_ = Url(base_ + 2, 7900 + base_ + 2);
  const std::string downlink_ = Url(base_ + 3, 7900 + base_ + 3);
  const std::string deaf_downlink_ = Url(base_ + 4, 7900 + base_ + 4);  // nobody sends there
  lcm::LCM sensor_lcm_{sensor_}, uplink_lcm_{uplink_}, downlink_lcm_{downlink_};
  // What the test hears: the agent's tiles and heartbeats on the uplink, the aggregator's
  // acknowledgements and heartbeats on the downlink.
  Heard<fleetmap::tempmap_tile_t> tiles_;
  Heard<fleetmap::status_t> agent_status_, aggregator_status_;
  Heard<fleetmap::tempmap_ack_t> acks_;
};

TEST_F(AgentKillTest, KilledWithUnacknowledgedMapsItSendsThemAgainAndNoneIsMergedTwice) {
  // 1. No aggregator: the agent closes temporary maps (the pallet), keeps them on disk and
  // sends them again and again, unanswered. SIGKILL once every scan went through.
  auto agent = StartAgent(downlink_);
  ASSERT_TRUE(FirstAgentStatus()) << Logs();
  const int64_t scans = Drive();
  ASSERT_TRUE(EveryScanHandled(scans)) << Logs();
  const int64_t closed = CounterOf(agent_status_.messages.back(), "tempmaps_closed");
  ASSERT_GE(closed, 1) << "no temporary map: the test proves nothing\n" << Logs();
  ASSERT_TRUE(Listen(10.0, [&] { return !tiles_.messages.empty(); })) << Logs();
  Kill(agent);
  const std::set<int32_t> pending = PendingFiles(state_dir());
  // Every closed map is on disk, and so is every map whose tiles went out (a map is saved
  // before it is sent). The one still being built at the kill is not closed: gone.
  EXPECT_EQ(static_cast<int64_t>(pending.size()), closed);
  for (int32_t s : TileSequences(tiles_)) EXPECT_TRUE(pending.count(s)) << "map " << s;
  EXPECT_TRUE(acks_.messages.empty());

  // 2. The aggregator starts, then the agent again on the same state folder but deaf to the
  // downlink: it reloads the maps and sends them, the aggregator merges each (MERGED, heard
  // by the test only), and the agent, which never hears it, is killed with all still pending.
  Process aggregator(AggregatorArgs(), dir_.File("aggregator_out.txt"),
                     dir_.File("aggregator_err.txt"));
  ASSERT_TRUE(Listen(20.0, [&] { return !aggregator_status_.messages.empty(); })) << Logs();
  size_t tiles_from = tiles_.messages.size(), acks_from = acks_.messages.size();
  agent = StartAgent(deaf_downlink_);
  ASSERT_TRUE(FirstAgentStatus()) << Logs();
  EXPECT_EQ(CounterOf(agent_status_.messages.front(), "tempmaps_pending"),
            static_cast<int64_t>(pending.size()));
  const auto all_answered = [&] {
    const auto answered = FinalAcks(acks_, acks_from);
    for (int32_t s : pending)
      if (!answered.count(s)) return false;
    return true;
  };
  ASSERT_TRUE(Listen(30.0, all_answered)) << Logs();
  EXPECT_EQ(TileSequences(tiles_, tiles_from), pending);  // resent, and no other map
  // Merged, or rejected by the alignment (a busy machine makes the agent skip scans and its
  // maps poorer): answered either way.
  std::set<int32_t> merged_acks;
  for (const auto& [sequence, outcomes] : FinalAcks(acks_, acks_from)) {
    EXPECT_TRUE(pending.count(sequence)) << "map " << sequence;
    EXPECT_TRUE(outcomes.front() == fleetmap::tempmap_ack_t::MERGED ||
                outcomes.front() == fleetmap::tempmap_ack_t::REJECTED)
        << "map " << sequence << ": " << int{outcomes.front()};
    if (outcomes.front() == fleetmap::tempmap_ack_t::MERGED) merged_acks.insert(sequence);
  }
  ASSERT_FALSE(merged_acks.empty()) << "nothing merged: the test proves little\n" << Logs();
  Kill(agent);
  EXPECT_EQ(PendingFiles(state_dir()), pending);

  // 3. Started again, hearing the aggregator: it sends the maps a third time; they are
  // DUPLICATE now (not merged again), and the agent is done with them.
  acks_from = acks_.messages.size();
  agent = StartAgent(downlink_);
  ASSERT_TRUE(FirstAgentStatus()) << Logs();
  ASSERT_TRUE(Listen(30.0, all_answered)) << Logs();
  for (const auto& [sequence, outcomes] : FinalAcks(acks_, acks_from))
    EXPECT_EQ(outcomes.front(), fleetmap::tempmap_ack_t::DUPLICATE) << "map " << sequence;
  ASSERT_TRUE(Listen(10.0, [&] {
    return CounterOf(agent_status_.messages.back(), "tempmaps_pending") == 0 &&
           PendingFiles(state_dir()).empty();
  })) << Logs();
  EXPECT_EQ(CounterOf(agent_status_.messages.back(), "maps_duplicate"),
            static_cast<int64_t>(pending.size()));

  // 4. Killed once more, the agent starts with nothing to send.
  Kill(agent);
  tiles_from = tiles_.messages.size();
  agent = StartAgent(downlink_);
  ASSERT_TRUE(FirstAgentStatus()) << Logs();
  EXPECT_EQ(CounterOf(agent_status_.messages.front(), "tempmaps_pending"), 0);
  EXPECT_EQ(tiles_.messages.size(), tiles_from);
  agent->Signal(SIGINT);
  EXPECT_EQ(agent->Wait(20.0), 0) << Logs();
  aggregator.Signal(SIGTERM);
  ASSERT_EQ(aggregator.Wait(20.0), 0) << Logs();

  // The aggregator's history: each map acknowledged MERGED merged exactly once, one version
  // per map.
  auto restored = aggregator::Aggregator::Open(world_.static_map(), aggregator::AggregatorOptions(),
                                               dir_.File("aggregator_state"));
  ASSERT_TRUE(restored.ok()) << restored.status().ToString();
  std::multiset<int32_t> merged;
  for (const aggregator::MergeCommit& c : restored->store().provenance().commits()) {
    EXPECT_EQ(c.source.vehicle_id, "v1");
    merged.insert(c.source.tempmap_sequence);
  }
  std::printf(
      "%lld maps closed before the kill, %zu kept, resent twice, %zu merged, version %llu\n",
      static_cast<long long>(closed), pending.size(), merged.size(),
      static_cast<unsigned long long>(restored->store().version()));
  EXPECT_EQ(merged, std::multiset<int32_t>(merged_acks.begin(), merged_acks.end()));
  EXPECT_EQ(restored->store().version(), merged_acks.size());
}

// The number after `key` on the last line of `path` that has it (-1 if none).
int64_t NumberAfter(const std::string& path, const std::string& key) {
  const std::string text = ReadText(path);
  const size_t at = text.rfind(key);
  return at == std::string::npos ? -1 : std::atoll(text.c_str() + at + key.size());
}

// Stopped (SIGINT) while it builds a temporary map, the agent closes the map, sends it, and
// before it exits hears it merged and takes the version it made: nothing is left to resend
// after a restart, and the map it writes at exit is the fleet's.
TEST_F(AgentKillTest, StoppedWhileBuildingItAwaitsTheMergeOfItsLastMap) {
  Process aggregator(AggregatorArgs(), dir_.File("aggregator_out.txt"),
                     dir_.File("aggregator_err.txt"));
  ASSERT_TRUE(Listen(20.0, [&] { return !aggregator_status_.messages.empty(); })) << Logs();
  auto agent = StartAgent(downlink_);
  ASSERT_TRUE(FirstAgentStatus()) << Logs();
  const int64_t scans = Drive();
  ASSERT_TRUE(EveryScanHandled(scans)) << Logs();
  // The pallet came into view at 3 s and the agent maps for 20 s after: at 16 s it still is.
  ASSERT_EQ(agent_status_.messages.back().state, "building")
      << "no map being built at the stop: the test proves nothing\n"
      << Logs();
  const size_t acks_from = acks_.messages.size(), tiles_from = tiles_.messages.size();
  agent->Signal(SIGINT);
  ASSERT_EQ(agent->Wait(20.0), 0) << Logs();
  EXPECT_TRUE(PendingFiles(state_dir()).empty()) << Logs();
  // The map closed at the stop: the tiles sent after the signal.
  ASSERT_TRUE(Listen(5.0, [&] { return tiles_.messages.size() > tiles_from; })) << Logs();
  const int32_t last_sequence = *TileSequences(tiles_, tiles_from).rbegin();
  EXPECT_TRUE(Listen(5.0, [&] { return FinalAcks(acks_, acks_from).count(last_sequence) > 0; }))
      << "the map closed at the stop was not answered\n"
      << Logs();
  aggregator.Signal(SIGTERM);
  ASSERT_EQ(aggregator.Wait(20.0), 0) << Logs();
  const int64_t fleet_version =
      NumberAfter(dir_.File("aggregator_out.txt"), "aggregator: version ");
  EXPECT_GE(fleet_version, 1) << Logs();
  EXPECT_EQ(NumberAfter(dir_.File("agent_out.txt"), " map_version "), fleet_version) << Logs();
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
