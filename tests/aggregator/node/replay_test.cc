#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <random>

#include "aggregator/node/log_replay.h"
#include "aggregator/node/map_hash.h"
#include "auth/key.h"
#include "auth/signer.h"
#include "core/map/map_io.h"
#include "tests/aggregator/node/node_test_util.h"
#include "tests/aggregator/node/process_util.h"
#include "tests/aggregator/test_files.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Encode;
using testing::PalletMap;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::TileMessages;

struct Event {
  int64_t utime = 0;
  std::string channel;
  std::vector<uint8_t> bytes;
};

// What an uplink logger records of a busy minute: two vehicles' maps with their tiles
// interleaved and repeated, a tile lost and sent again later, a map resent after its merge,
// requests, junk, and downlink traffic the replay must skip.
std::vector<Event> UplinkTraffic() {
  std::vector<core::TempMap> maps = PalletMaps();
  maps.push_back(PalletMap(1, "v2", 1));
  maps.push_back(PalletMap(3, "v2", 2));
  std::mt19937 rng(21);
  std::vector<Event> events;
  int64_t t = 1'700'000'000'000'000;
  for (size_t m = 0; m < maps.size(); ++m) {
    auto tiles = TileMessages(maps[m], t);
    std::vector<size_t> order(tiles.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    const size_t lost = order.back();
    order.pop_back();
    order.push_back(order[2]);
    const std::string channel = lcmtypes::TempMapChannel(maps[m].vehicle_id);
    for (size_t i : order) events.push_back({t += 800, channel, tiles[i]});
    events.push_back({t += 1000, "TEMPMAP_ACK", {1, 2, 3}});
    events.push_back({t += 1000, channel, {9, 9, 9}});
    events.push_back({t += 1'000'000, channel, TileMessages(maps[m], t)[lost]});
    if (m == 2) {  // the MERGED acknowledgement of map 0 was lost: all of it again
      for (const auto& tile : TileMessages(maps[0], t))
        events.push_back({t += 500, "TEMPMAP_v1", tile});
    }
    fleetmap::map_request_t request;
    request.utime = t;
    request.vehicle_id = "v3";
    request.have_version = m % 2 ? -1 : 0;
    request.num_tiles = 0;
    events.push_back({t += 300, lcmtypes::kMapRequestChannel, Encode(request)});
    events.push_back({t += 300, "MAP_DELTA", {0, 0}});
    t += 7'000'000;
  }
  return events;
}

void WriteLog(const std::string& path, const std::vector<Event>& events) {
  lcm::LogFile log(path, "w");
  ASSERT_TRUE(log.good()) << path;
  for (const Event& e : events) {
    lcm::LogEvent ev;
    ev.eventnum = 0;
    ev.timestamp = e.utime;
    ev.channel = e.channel;
    ev.datalen = static_cast<int32_t>(e.bytes.size());
    ev.data = const_cast<uint8_t*>(e.bytes.data());
    ASSERT_EQ(log.writeEvent(&ev), 0);
  }
}

class AggregatorNodeReplayTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(core::SaveMapServerMap(aggregator::testing::HallMap(), map_yaml_).ok());
    events_ = UplinkTraffic();
    WriteLog(log_, events_);
  }

  // What the binary prints for a replay of `logs`, and how long it took.
  std::string RunReplay(const std::vector<std::string>& logs, const std::string& final_map,
                        double* seconds = nullptr, const std::vector<std::string>& flags = {}) {
    std::vector<std::string> args = {
        testing::AggregatorBinary(), "--map", map_yaml_, "--quiet", "--final-map", final_map};
    args.insert(args.end(), flags.begin(), flags.end());
    args.push_back("--replay");
    args.insert(args.end(), logs.begin(), logs.end());
    const std::string out = folder_.File("stdout" + std::to_string(runs_));
    const std::string err = folder_.File("stderr" + std::to_string(runs_++));
    const auto start = std::chrono::steady_clock::now();
    testing::Process p(args, out, err);
    EXPECT_EQ(p.Wait(50.0), 0) << testing::ReadText(err);
    if (seconds)
      *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return testing::FinalLineOf(testing::ReadText(out));
  }

  fleetmap::testing::ScratchFolder folder_;
  std::string map_yaml_ = folder_.File("hall.yaml");
  std::string log_ = folder_.File("uplink.lcmlog");
  std::vector<Event> events_;
  int runs_ = 0;
};

TEST_F(AggregatorNodeReplayTest, AReplayMergesExactlyAsTheNodeInMemoryAndTwoReplaysAgree) {
  // The node in memory, as the live process runs it, on the map the binary loads.
  auto loaded = core::LoadMapServerMap(map_yaml_);
  ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
  auto aggregator = Aggregator::Create(loaded->grid, AggregatorOptions{});
  ASSERT_TRUE(aggregator.ok());
  RecordingPublisher out;
  auto node = AggregatorNode::Create(std::move(aggregator).value(), {}, &out, {}, 0.0);
  ASSERT_TRUE(node.ok());
  for (const Event& e : events_) {
    if (!IsUplinkChannel(e.channel)) continue;
    const double t = lcmtypes::FromUtime(e.utime);
    (*node)->OnMessage(e.channel, e.bytes.data(), static_cast<int>(e.bytes.size()), t);
    (*node)->Tick(t);
  }
  const NodeCounters& c = (*node)->counters();
  EXPECT_EQ(c.maps_merged, 6);
  EXPECT_GT(c.duplicates, 0);
  EXPECT_GT(c.malformed_messages, 0);
  const std::string expected = (*node)->FinalLine();
  EXPECT_EQ(expected, FinalLine((*node)->aggregator().store().version(),
                                MapHash((*node)->aggregator().store().current_map()), 6, 0));

  double seconds = 0.0;
  const std::string first = RunReplay({log_}, folder_.File("final1.yaml"), &seconds);
  const std::string second = RunReplay({log_}, folder_.File("final2.yaml"));
  std::printf("replay of %zu events: %.3f s (process start to exit)\n", events_.size(), seconds);
  ::testing::Test::RecordProperty("replay_ms", static_cast<int>(seconds * 1000));
  EXPECT_EQ(first, expected);
  EXPECT_EQ(second, expected);

  // The final map on disk is the node's current map, cell for cell (tri-state).
  auto final_map = core::LoadMapServerMap(folder_.File("final1.yaml"));
  ASSERT_TRUE(final_map.ok()) << final_map.status().ToString();
  const core::OccupancyGrid& current = (*node)->aggregator().store().current_map();
  ASSERT_TRUE(final_map->grid.geometry() == current.geometry());
  int differ = 0;
  for (int y = 0; y < current.geometry().height(); ++y)
    for (int x = 0; x < current.geometry().width(); ++x)
      differ += final_map->grid.state({x, y}) != current.state({x, y});
  EXPECT_EQ(differ, 0);
  EXPECT_TRUE(std::filesystem::exists(folder_.File("final1.png")));
}

TEST_F(AggregatorNodeReplayTest, SeveralLogsAreMergedByEventTime) {
  std::vector<Event> a, b;
  for (size_t i = 0; i < events_.size(); ++i) (i % 3 ? a : b).push_back(events_[i]);
  WriteLog(folder_.File("a.lcmlog"), a);
  WriteLog(folder_.File("b.lcmlog"), b);
  const std::string whole = RunReplay({log_}, folder_.File("w.yaml"));
  const std::string split =
      RunReplay({folder_.File("b.lcmlog"), folder_.File("a.lcmlog")}, folder_.File("s.yaml"));
  EXPECT_FALSE(whole.empty());
  EXPECT_EQ(split, whole);
}

// A log recorded from a keyed fleet (docs/security.md): every uplink message signed by its
// sender. Replayed offline with the same key it gives the same map as the unsigned log (the
// replay windows start empty and read each sender's messages in order); without a key the
// trailers are split off unchecked; with another key nothing counts.
TEST_F(AggregatorNodeReplayTest, ASignedLogReplaysWithTheKeyToTheSameMap) {
  const auth::Key key = auth::GenerateKey();
  std::map<std::string, auth::Signer> signers;
  std::vector<Event> signed_events = events_;
  for (Event& e : signed_events) {
    if (!IsUplinkChannel(e.channel)) continue;
    const std::string sender = e.channel.rfind("TEMPMAP_", 0) == 0 ? e.channel.substr(8) : "v3";
    auto it = signers.try_emplace(sender, key, sender, auth::FirstSequence(1.7e9)).first;
    it->second.Seal(e.channel, e.bytes);
  }
  WriteLog(folder_.File("signed.lcmlog"), signed_events);
  const std::string key_file = folder_.File("fleet.key");
  std::ofstream(key_file) << auth::KeyToHex(key) << "\n";
  ::chmod(key_file.c_str(), 0600);
  const std::string other_key = folder_.File("other.key");
  std::ofstream(other_key) << auth::KeyToHex(auth::GenerateKey()) << "\n";
  ::chmod(other_key.c_str(), 0600);

  const std::string plain = RunReplay({log_}, folder_.File("p.yaml"));
  ASSERT_NE(plain.find("merged 6"), std::string::npos) << plain;
  const std::string signed_log = folder_.File("signed.lcmlog");
  EXPECT_EQ(RunReplay({signed_log}, folder_.File("k.yaml"), nullptr, {"--key-file", key_file}),
            plain);
  EXPECT_EQ(RunReplay({signed_log}, folder_.File("n.yaml")), plain);
  const std::string wrong =
      RunReplay({signed_log}, folder_.File("w.yaml"), nullptr, {"--key-file", other_key});
  EXPECT_NE(wrong.find("version 0 "), std::string::npos) << wrong;
  // The unsigned log with a key: nothing counts either.
  EXPECT_NE(
      RunReplay({log_}, folder_.File("u.yaml"), nullptr, {"--key-file", key_file}).find("merged 0"),
      std::string::npos);
}

TEST_F(AggregatorNodeReplayTest, AKeyFileOthersCanReadIsRefusedWithTheFix) {
  const std::string key_file = folder_.File("open.key");
  std::ofstream(key_file) << auth::KeyToHex(auth::GenerateKey()) << "\n";
  ::chmod(key_file.c_str(), 0644);
  testing::Process p(
      {testing::AggregatorBinary(), "--map", map_yaml_, "--key-file", key_file, "--replay", log_},
      folder_.File("o"), folder_.File("e"));
  EXPECT_EQ(p.Wait(30.0), 1);
  const std::string err = testing::ReadText(folder_.File("e"));
  EXPECT_NE(err.find("chmod 600"), std::string::npos) << err;
}

TEST_F(AggregatorNodeReplayTest, AMissingLogIsAClearError) {
  testing::Process p(
      {testing::AggregatorBinary(), "--map", map_yaml_, "--replay", folder_.File("nope.lcmlog")},
      folder_.File("o"), folder_.File("e"));
  EXPECT_EQ(p.Wait(30.0), 1);
  EXPECT_NE(testing::ReadText(folder_.File("e")).find("nope.lcmlog: no such log"),
            std::string::npos);
}

}  // namespace
}  // namespace fleetmap::aggregator::node
