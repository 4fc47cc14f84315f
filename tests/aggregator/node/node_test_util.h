// Shared pieces of the aggregator node tests: the hall of tests/aggregator with a pallet,
// temporary maps of it as LCM tile messages, a publisher that records what the node sends,
// and a node made in memory or on a state folder.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "aggregator/node/aggregator_node.h"
#include "auth/trailer.h"
#include "fleetmap/candidates_free_t.hpp"
#include "fleetmap/candidates_held_t.hpp"
#include "fleetmap/map_delta_t.hpp"
#include "fleetmap/map_keyframe_t.hpp"
#include "fleetmap/map_request_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"
#include "tests/aggregator/test_hall.h"
#include "tests/edge/recording_publisher.h"

namespace fleetmap::aggregator::node::testing {

using edge::testing::RecordingPublisher;
using edge::testing::SentMessage;

template <typename T>
std::vector<uint8_t> Encode(const T& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// One message per tile, in tile order, each stamped `utime` (microseconds).
// CANDIDATES_FREE_: `vehicle` saw `cells` of map version 1 free on a pass starting at
// `first_pass_s` and lasting 0.5 s.
inline std::vector<uint8_t> SeenFreeBytes(const std::string& vehicle,
                                          const std::vector<int32_t>& cells, double first_pass_s,
                                          int64_t utime = 1'700'000'000'000'000) {
  fleetmap::candidates_free_t m;
  m.utime = utime;
  m.vehicle_id = vehicle;
  m.map_version = 1;
  m.first_pass_utime = lcmtypes::ToUtime(first_pass_s);
  m.last_pass_utime = lcmtypes::ToUtime(first_pass_s + 0.5);
  m.cells = cells;
  m.num_cells = static_cast<int32_t>(cells.size());
  return Encode(m);
}

// CANDIDATES_HELD_: `vehicle` saw `cells` of map version 1 held from `since_s` to `until_s`.
inline std::vector<uint8_t> HeldBytes(const std::string& vehicle, const std::vector<int32_t>& cells,
                                      double since_s, double until_s,
                                      int64_t utime = 1'700'000'000'000'000) {
  fleetmap::candidates_held_t m;
  m.utime = utime;
  m.vehicle_id = vehicle;
  m.map_version = 1;
  m.base_utime = lcmtypes::ToUtime(since_s);
  m.cells = cells;
  m.num_cells = static_cast<int32_t>(cells.size());
  m.since_ms.assign(cells.size(), 0);
  m.until_ms.assign(cells.size(), static_cast<int32_t>((until_s - since_s) * 1e3));
  return Encode(m);
}

inline std::vector<std::vector<uint8_t>> TileMessages(const core::TempMap& map, int64_t utime) {
  std::vector<std::vector<uint8_t>> out;
  for (const core::TempMapTile& t : core::SplitTempMap(map))
    out.push_back(Encode(lcmtypes::ToMessage(t, utime)));
  return out;
}

// The tile indices an acknowledgement names as received.
inline std::vector<int32_t> Received(const fleetmap::tempmap_ack_t& ack) {
  return std::vector<int32_t>(ack.received_tiles.begin(), ack.received_tiles.end());
}

// The hall of tests/aggregator with a pallet at (6, 7), and temporary maps of it from a
// vehicle driving past, 20 s apart, with anchor errors of up to 0.1 m and 1.5 deg.
inline core::OccupancyGrid PalletWorld() {
  return aggregator::testing::HallMap(0.0, {{{6.0, 7.0}, {1.2, 0.8}}});
}

inline core::TempMap PalletMap(int i, const std::string& vehicle = "v1", int32_t sequence = -1) {
  aggregator::testing::TempMapSpec spec;
  spec.start = {3.013 + 0.7 * (i % 4), 5.027, 0.0};
  spec.anchor_error = {0.1 * (i % 3) - 0.1, 0.07 * (i % 4) - 0.1, ((i % 4) - 1.5) * M_PI / 180};
  spec.vehicle = vehicle;
  spec.sequence = sequence >= 0 ? sequence : i + 1;
  spec.start_s = 1000.0 + 20.0 * i;
  spec.end_s = spec.start_s + 10.0;
  spec.seed = 11 + i;
  return aggregator::testing::BuildTempMap(PalletWorld(), spec);
}

// Four maps of v1 (sequences 1..4), built once.
inline const std::vector<core::TempMap>& PalletMaps() {
  static const std::vector<core::TempMap>* maps = [] {
    auto* m = new std::vector<core::TempMap>();
    for (int i = 0; i < 4; ++i) m->push_back(PalletMap(i));
    return m;
  }();
  return *maps;
}

// The test's log lines, for checking that a cause is logged once.
struct LogLines {
  std::vector<std::string> lines;
  LogSink Sink() {
    return [this](LogLevel, const std::string& line) { lines.push_back(line); };
  }
  int Containing(const std::string& text) const {
    int n = 0;
    for (const std::string& l : lines) n += l.find(text) != std::string::npos;
    return n;
  }
};

// A node on the hall's static map: in memory, or persisted in `state_dir` (its tile spool
// in state_dir/incoming).
inline std::unique_ptr<AggregatorNode> MakeNode(Publisher* publisher, LogSink log = {},
                                                const std::string& state_dir = "",
                                                AggregatorNodeOptions options = {},
                                                double now_s = 0.0) {
  AggregatorOptions aggregator_options;
  auto aggregator =
      state_dir.empty()
          ? Aggregator::Create(aggregator::testing::HallMap(), aggregator_options)
          : Aggregator::Open(aggregator::testing::HallMap(), aggregator_options, state_dir);
  EXPECT_TRUE(aggregator.ok()) << aggregator.status().ToString();
  if (!state_dir.empty()) options.spool_dir = state_dir + "/incoming";
  auto node = AggregatorNode::Create(std::move(aggregator).value(), options, publisher,
                                     std::move(log), now_s);
  EXPECT_TRUE(node.ok()) << node.status().ToString();
  return std::move(node).value();
}

// Hands every message to the node on TEMPMAP_<vehicle> at `now_s`.
inline void Feed(AggregatorNode& node, const std::string& vehicle,
                 const std::vector<std::vector<uint8_t>>& messages, double now_s) {
  for (const auto& m : messages)
    node.OnMessage(lcmtypes::TempMapChannel(vehicle), m.data(), static_cast<int>(m.size()), now_s);
}

}  // namespace fleetmap::aggregator::node::testing
