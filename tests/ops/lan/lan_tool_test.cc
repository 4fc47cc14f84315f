// ops/lan: the figures fleetmap-lan-tool reads from recorded LAN runs, on tiny hand-made
// LCM logs with known answers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "core/codec/map_codec.h"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "fleetmap/tempmap_tile_t.hpp"
#include "lcmtypes/transport_convert.h"
#include "ops/lan/ack_delays.h"
#include "ops/lan/change_cost.h"
#include "ops/lan/codec_sweep.h"
#include "ops/lan/lan_log.h"
#include "ops/lan/map_resample.h"
#include "ops/lan/status_summary.h"

namespace fleetmap::ops::lan {
namespace {

template <typename T>
LogMessage Message(int64_t utime, const std::string& channel, const T& msg) {
  LogMessage m;
  m.recv_utime = utime;
  m.channel = channel;
  m.data.resize(msg.getEncodedSize());
  msg.encode(m.data.data(), 0, static_cast<int>(m.data.size()));
  return m;
}

fleetmap::status_t Status(const std::string& process, int64_t utime,
                          const std::vector<std::pair<std::string, int64_t>>& counters) {
  fleetmap::status_t s;
  s.utime = utime;
  s.process = process;
  s.map_version = 3;
  s.state = "running";
  s.authenticated = false;
  for (const auto& [name, value] : counters) {
    s.counter_names.push_back(name);
    s.counter_values.push_back(value);
  }
  s.num_counters = static_cast<int32_t>(counters.size());
  return s;
}

// A 64 x 64 grid: free, with an occupied wall along x = 10 and unknown corners.
core::OccupancyGrid Room(int width = 64, int height = 64) {
  core::OccupancyGrid grid(core::GridGeometry(0.05, width, height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool corner = x < 4 && y < 4;
      grid.SetState({x, y}, corner    ? core::CellState::kUnknown
                            : x == 10 ? core::CellState::kOccupied
                                      : core::CellState::kFree);
    }
  }
  return grid;
}

core::DeltaTile Delta(int32_t base_version, int32_t index, int32_t count) {
  core::DeltaTile d;
  d.base_version = base_version;
  d.index = index;
  d.count = count;
  d.tile = {index, 0};
  d.frame = core::EncodeWindow(Room(), {0, 0, 64, 64});
  return d;
}

TEST(StatusSummaryTest, KeepsEachProcessesLatestHeartbeatBeforeTheCutOff) {
  const std::vector<LogMessage> log = {
      Message(10, "STATUS_agent_v1", Status("agent_v1", 100, {{"tempmaps_closed", 1}})),
      Message(11, "STATUS_agent_v2", Status("agent_v2", 100, {{"tempmaps_closed", 4}})),
      Message(12, "STATUS_agent_v1", Status("agent_v1", 300, {{"tempmaps_closed", 3}})),
      Message(13, "STATUS_agent_v1", Status("agent_v1", 200, {{"tempmaps_closed", 2}})),
      Message(14, "STATUS_aggregator", Status("aggregator", 150, {{"maps_merged", 5}})),
      LogMessage{15, "STATUS_agent_v3", {1, 2, 3}},
  };
  const StatusSummary all = SummarizeStatus(log);
  ASSERT_EQ(all.processes.size(), 3u);
  EXPECT_EQ(all.processes.at("agent_v1").counters.at("tempmaps_closed"), 3);
  EXPECT_EQ(all.processes.at("agent_v1").heartbeats, 3);
  EXPECT_EQ(all.malformed, 1);
  const std::string lines = StatusFigureLines(all);
  EXPECT_NE(lines.find("status.agents.tempmaps_closed 7 count\n"), std::string::npos) << lines;
  EXPECT_NE(lines.find("status.agents.count 2 count\n"), std::string::npos);
  EXPECT_NE(lines.find("status.aggregator.maps_merged 5 count\n"), std::string::npos);

  const StatusSummary before = SummarizeStatus(log, 250);  // the heartbeat at 300 is left out
  EXPECT_EQ(before.processes.at("agent_v1").counters.at("tempmaps_closed"), 2);
}

TEST(CodecSweepTest, TheSentCodecGivesTheSentBytesAndRawIsOneBytePerCell) {
  const fleetmap::map_delta_t delta = lcmtypes::ToMessage(Delta(0, 0, 1), 1);
  const std::vector<LogMessage> log = {Message(1, "MAP_DELTA", delta),
                                       Message(2, "MAP_DELTA", delta),
                                       Message(3, "POSE_v1", delta)};  // not a map channel
  const auto groups = RecodeMapMessages(log, DefaultCodecVariants());
  ASSERT_EQ(groups.size(), 1u);
  const ChannelGroupBytes& g = groups.at("MAP_DELTA");
  EXPECT_EQ(g.messages, 2);
  EXPECT_EQ(g.undecodable, 0);
  EXPECT_EQ(g.sent_bytes, 2 * int64_t(log[0].data.size()));
  EXPECT_EQ(g.bytes_by_variant.at("zstd3"), g.sent_bytes);  // the default codec, unchanged
  const int64_t frame = int64_t(delta.tile.payload.size());
  const int64_t raw_frame = core::kCodecHeaderBytes + 64 * 64 + core::kCodecTrailerBytes;
  EXPECT_EQ(g.bytes_by_variant.at("raw8"), g.sent_bytes + 2 * (raw_frame - frame));
  const int64_t packed_frame = core::kCodecHeaderBytes + 64 * 64 / 4 + core::kCodecTrailerBytes;
  EXPECT_EQ(g.bytes_by_variant.at("none"), g.sent_bytes + 2 * (packed_frame - frame));
  EXPECT_LT(g.bytes_by_variant.at("zstd19"), g.bytes_by_variant.at("none"));
  EXPECT_NE(CodecFigureLines(groups).find("codec.MAP_DELTA.raw8.bytes "), std::string::npos);
}

TEST(CodecSweepTest, AFrameThatDoesNotDecodeIsCountedNotRecoded) {
  fleetmap::map_delta_t delta = lcmtypes::ToMessage(Delta(0, 0, 1), 1);
  delta.tile.payload[5] ^= 0x5a;  // breaks the CRC
  const auto groups = RecodeMapMessages({Message(1, "MAP_DELTA", delta)}, DefaultCodecVariants());
  EXPECT_EQ(groups.at("MAP_DELTA").messages, 0);
  EXPECT_EQ(groups.at("MAP_DELTA").undecodable, 1);
}

TEST(ChangeCostTest, DeltaOnceKeyframeWholeAndAnOccupancyGridOfTheMap) {
  core::KeyframeTile k;
  k.version = 1;
  k.geometry = core::GridGeometry(0.05, 64, 128);
  k.count = 2;
  k.frame = core::EncodeWindow(Room(), {0, 0, 64, 64});
  std::vector<LogMessage> log;
  const auto d0 = lcmtypes::ToMessage(Delta(0, 0, 2), 1);
  const auto d1 = lcmtypes::ToMessage(Delta(0, 1, 2), 1);
  log.push_back(Message(1, "MAP_DELTA", d0));
  log.push_back(Message(2, "MAP_DELTA", d1));
  log.push_back(Message(3, "MAP_DELTA", d0));  // a resend: counted once
  for (int32_t i = 0; i < 2; ++i) {
    k.index = i;
    k.tile = {0, i};
    log.push_back(Message(4 + i, "MAP_KEYFRAME", lcmtypes::ToMessage(k, 1)));
  }
  const ChangeCost c = MeasureChangeCost(log);
  EXPECT_EQ(c.changes, 1);
  EXPECT_DOUBLE_EQ(c.delta_bytes_mean, double(log[0].data.size() + log[1].data.size()));
  EXPECT_DOUBLE_EQ(c.delta_tiles_mean, 2.0);
  EXPECT_EQ(c.keyframes_complete, 1);
  EXPECT_DOUBLE_EQ(c.keyframe_bytes, double(log[3].data.size() + log[4].data.size()));
  EXPECT_EQ(c.map_cells, 64 * 128);
  EXPECT_EQ(c.occupancy_grid_bytes, 64 * 128 + kOccupancyGridHeaderBytes);
}

fleetmap::tempmap_tile_t Tile(const std::string& vehicle, int32_t sequence) {
  fleetmap::tempmap_tile_t t{};
  t.vehicle_id = vehicle;
  t.tempmap_seq = sequence;
  return t;
}

fleetmap::tempmap_ack_t Ack(const std::string& vehicle, int32_t sequence, int8_t outcome) {
  fleetmap::tempmap_ack_t a{};
  a.vehicle_id = vehicle;
  a.tempmap_seq = sequence;
  a.outcome = outcome;
  return a;
}

// From each map's last tile to its final ack; PENDING acks are not answers; an ack whose map
// was never logged is counted, not timed.
TEST(AckDelaysTest, FromAMapsLastTileToItsFinalAck) {
  using fleetmap::tempmap_ack_t;
  const std::vector<LogMessage> log = {
      Message(1'000'000, "TEMPMAP_v1", Tile("v1", 1)),
      Message(2'000'000, "TEMPMAP_v1", Tile("v1", 1)),
      Message(2'500'000, "TEMPMAP_ACK", Ack("v1", 1, tempmap_ack_t::PENDING)),
      Message(3'000'000, "TEMPMAP_ACK", Ack("v1", 1, tempmap_ack_t::MERGED)),
      Message(3'100'000, "TEMPMAP_ACK", Ack("v2", 7, tempmap_ack_t::REJECTED)),
      Message(4'000'000, "TEMPMAP_v1", Tile("v1", 2)),
      Message(4'200'000, "TEMPMAP_ACK", Ack("v1", 2, tempmap_ack_t::DUPLICATE)),
  };
  const AckDelays d = MeasureAckDelays(log);
  ASSERT_EQ(d.delays_s.size(), 2u);
  EXPECT_DOUBLE_EQ(d.delays_s[0], 1.0);
  EXPECT_NEAR(d.delays_s[1], 0.2, 1e-9);
  EXPECT_EQ(d.untimed, 1);
  const std::string lines = AckDelayFigureLines(d);
  EXPECT_NE(lines.find("acks.count 2 count\n"), std::string::npos) << lines;
  EXPECT_NE(lines.find("acks.delay_s.median 0.2 s\n"), std::string::npos) << lines;
  EXPECT_NE(lines.find("acks.delay_s.p95 1 s\n"), std::string::npos) << lines;
  EXPECT_EQ(AckDelayFigureLines({}).find("delay_s"), std::string::npos) << "no figure over nothing";
}

TEST(MapResampleTest, OccupiedWinsThenHalfFreeIsFree) {
  core::OccupancyGrid fine(core::GridGeometry(0.05, 5, 4, core::Pose2(1.0, 2.0, 0.0)));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) fine.SetState({x, y}, core::CellState::kFree);
  fine.SetState({1, 1}, core::CellState::kOccupied);  // block (0, 0): occupied
  fine.SetState({2, 2}, core::CellState::kUnknown);   // block (1, 1): 3 free of 4
  fine.SetState({3, 2}, core::CellState::kUnknown);
  fine.SetState({2, 3}, core::CellState::kUnknown);  // ... now 1 free of 4: unknown
  const core::OccupancyGrid coarse = ResampleMap(fine, 2);
  ASSERT_EQ(coarse.geometry().width(), 3);  // the last column covers one fine column
  ASSERT_EQ(coarse.geometry().height(), 2);
  EXPECT_DOUBLE_EQ(coarse.geometry().resolution_m(), 0.1);
  EXPECT_DOUBLE_EQ(coarse.geometry().origin().x_m, 1.0);
  EXPECT_EQ(coarse.state({0, 0}), core::CellState::kOccupied);
  EXPECT_EQ(coarse.state({1, 0}), core::CellState::kFree);
  EXPECT_EQ(coarse.state({1, 1}), core::CellState::kUnknown);
  EXPECT_EQ(coarse.state({2, 1}), core::CellState::kFree);
}

TEST(LanLogTest, ReadsLogsMergedByReceiveTimeAndRefusesAMissingOne) {
  const std::string path = ::testing::TempDir() + "lan_log_test_" + std::to_string(getpid());
  {
    lcm::LogFile log(path, "w");
    ASSERT_TRUE(log.good());
    std::vector<uint8_t> bytes = {1, 2, 3};
    for (int64_t t : {30, 10}) {
      lcm::LogEvent ev;
      ev.eventnum = 0;
      ev.timestamp = t;
      ev.channel = "X";
      ev.datalen = 3;
      ev.data = bytes.data();
      ASSERT_EQ(log.writeEvent(&ev), 0);
    }
  }
  auto messages = ReadLogs({path});
  std::remove(path.c_str());
  ASSERT_TRUE(messages.ok()) << messages.status().ToString();
  ASSERT_EQ(messages->size(), 2u);
  EXPECT_EQ((*messages)[0].recv_utime, 10);
  EXPECT_EQ((*messages)[1].data.size(), 3u);
  EXPECT_FALSE(ReadLogs({path}).ok());
}

}  // namespace
}  // namespace fleetmap::ops::lan
