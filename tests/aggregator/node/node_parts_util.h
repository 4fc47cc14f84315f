// The aggregator node's shared state, its downlink and its committer, wired by hand as
// AggregatorNode wires them, on the hall of tests/aggregator: a part's test builds the part
// on these and drives it through its own interface, watching what it sends, counts and logs.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "aggregator/node/map_committer.h"
#include "aggregator/node/map_publisher.h"
#include "aggregator/node/node_reporting.h"
#include "aggregator/node/tile_spool.h"
#include "aggregator/node/vehicle_limits.h"
#include "core/codec/temp_map_tiles.h"
#include "tests/aggregator/node/node_test_util.h"

namespace fleetmap::aggregator::node::testing {

// The hall's aggregator: in memory, or persisted in `state_dir`.
inline Aggregator HallAggregator(const std::string& state_dir = "") {
  AggregatorOptions options;
  auto aggregator = state_dir.empty()
                        ? Aggregator::Create(aggregator::testing::HallMap(), options)
                        : Aggregator::Open(aggregator::testing::HallMap(), options, state_dir);
  EXPECT_TRUE(aggregator.ok()) << aggregator.status().ToString();
  return std::move(aggregator).value();
}

// options.spool_dir opened, or a disabled spool.
inline TileSpool OpenSpool(const std::string& folder) {
  if (folder.empty()) return TileSpool();
  auto spool = TileSpool::Open(folder);
  EXPECT_TRUE(spool.ok()) << spool.status().ToString();
  return std::move(spool).value();
}

inline MapKey KeyOf(const core::TempMap& map) { return {map.vehicle_id, map.sequence}; }

inline int32_t TileCount(const core::TempMap& map) {
  return static_cast<int32_t>(core::SplitTempMap(map).size());
}

// The channels of what was sent, in order.
inline std::vector<std::string> Channels(const RecordingPublisher& out) {
  std::vector<std::string> channels;
  for (const SentMessage& m : out.sent) channels.push_back(m.channel);
  return channels;
}

struct NodeParts {
  // `publishing` false: no Publisher, as in a replay.
  explicit NodeParts(AggregatorNodeOptions node_options = {}, const std::string& state_dir = "",
                     bool publishing = true)
      : options(std::move(node_options)),
        aggregator(HallAggregator(state_dir)),
        log(lines.Sink()),
        spool(OpenSpool(options.spool_dir)),
        limits(options.limits),
        publisher(aggregator, options, publishing ? &out : nullptr, report()),
        committer(aggregator, options, spool, limits, publisher, report()) {}
  NodeReporting report() { return {counters, log}; }

  RecordingPublisher out;
  LogLines lines;
  const AggregatorNodeOptions options;
  Aggregator aggregator;
  NodeCounters counters;
  CauseLog log;
  TileSpool spool;
  VehicleLimits limits;
  MapPublisher publisher;
  MapCommitter committer;
};

}  // namespace fleetmap::aggregator::node::testing
