#include "aggregator/node/map_request_answerer.h"

#include <algorithm>
#include <string>

#include "aggregator/node/map_key.h"
#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {
namespace {

// The rolling keyframe's bytes: at most keyframe_share of the downlink's budget.
core::PacerOptions RollingShare(const AggregatorNodeOptions& options) {
  core::PacerOptions share;
  share.rate_per_s = 1e9;  // no limit in messages: the downlink's own pacer has one
  share.burst = 1e9;
  share.bytes_per_s = options.keyframe_share * options.downlink_bytes_per_s;
  share.burst_bytes = options.max_message_bytes;
  return share;
}

}  // namespace

MapRequestAnswerer::MapRequestAnswerer(const Aggregator& aggregator,
                                       const AggregatorNodeOptions& options,
                                       MapPublisher& publisher, NodeReporting report, double now_s)
    : aggregator_(aggregator),
      options_(options),
      publisher_(publisher),
      report_(report),
      schedule_(core::TileLayout(aggregator.store().current_map().geometry(),
                                 aggregator.options().store.tiles.tile_size_cells)
                    .num_tiles(),
                options_.keyframe_period_s, now_s),
      next_candidates_s_(now_s + options_.keyframe_period_s),
      rolling_share_(RollingShare(options_)) {}

void MapRequestAnswerer::OnRequest(const void* data, int size) {
  auto msg = lcmtypes::Decode<fleetmap::map_request_t>(data, size);
  if (!msg.ok()) {
    report_.Refuse("MAP_REQUEST: malformed", report_.counters.malformed_messages,
                   "MAP_REQUEST: not a map_request_t: " + msg.status().ToString());
    return;
  }
  if (!Possible(*msg)) return;
  ++report_.counters.requests;
  Queue(*msg);
}

bool MapRequestAnswerer::Possible(const fleetmap::map_request_t& request) {
  const core::TileLayout layout(aggregator_.store().current_map().geometry(),
                                aggregator_.options().store.tiles.tile_size_cells);
  const bool tiles_ok = request.num_tiles <= layout.num_tiles() &&
                        std::all_of(request.tiles.begin(), request.tiles.end(),
                                    [&](int32_t t) { return t >= 0 && t < layout.num_tiles(); });
  if (request.vehicle_id.size() <= kMaxUplinkVehicleIdBytes && request.have_version >= -1 &&
      tiles_ok)
    return true;
  report_.Refuse("MAP_REQUEST: impossible", report_.counters.bad_requests,
                 "MAP_REQUEST from '" + request.vehicle_id.substr(0, kMaxUplinkVehicleIdBytes) +
                     "' refused: have_version " + std::to_string(request.have_version) + ", " +
                     std::to_string(request.num_tiles) + " tiles (the map has " +
                     std::to_string(layout.num_tiles()) + ")");
  return false;
}

void MapRequestAnswerer::Queue(const fleetmap::map_request_t& request) {
  const CurrentMapStore& store = aggregator_.store();
  const int64_t have = request.have_version;
  const int64_t current = static_cast<int64_t>(store.version());
  if (!request.tiles.empty() || have < 0 || have > current) {
    schedule_.Ask(request.tiles);  // (a vehicle ahead of us: our state was lost)
  } else if (have < current) {
    const bool retained =
        store.Delta(static_cast<uint64_t>(have)).ok() && store.Delta(current - 1).ok();
    if (retained) {
      const auto from = static_cast<uint64_t>(have);
      deltas_from_ = deltas_from_ ? std::min(*deltas_from_, from) : from;
    } else {
      schedule_.Ask({});
    }
  }  // have == current: the vehicle is up to date
}

void MapRequestAnswerer::Tick(double now_s) {
  SendDeltas(now_s);
  if (options_.keyframe_period_s > 0 && now_s >= next_candidates_s_) {
    publisher_.SendCandidates(now_s);  // for vehicles that joined since they last changed
    next_candidates_s_ = now_s + options_.keyframe_period_s;
  }
  SendKeyframeTiles(now_s);
}

void MapRequestAnswerer::SendDeltas(double now_s) {
  if (!deltas_from_) return;
  const CurrentMapStore& store = aggregator_.store();
  for (uint64_t v = *deltas_from_; v < store.version(); ++v) {
    auto delta = store.Delta(v);
    if (!delta.ok()) {  // dropped meanwhile: keyframe tiles answer instead
      schedule_.Ask({});
      break;
    }
    publisher_.SendDelta(*delta, now_s);
    ++report_.counters.deltas_resent;
  }
  deltas_from_.reset();
}

void MapRequestAnswerer::SendKeyframeTiles(double now_s) {
  if (!publisher_.enabled()) return;
  while (publisher_.room_bytes() > 0) {
    std::optional<int32_t> tile = schedule_.NextAsked();
    const bool rolling = !tile;
    if (rolling && rolling_share_.MaySend(now_s)) tile = schedule_.NextRolling(now_s);
    if (!tile) break;
    const std::vector<int32_t> only = {*tile};
    const size_t bytes = publisher_.SendKeyframe(&only, now_s);
    if (rolling) rolling_share_.Sent(0, bytes);
  }
  report_.counters.keyframe_rounds = schedule_.rounds();
  report_.counters.asked_tiles_sent = schedule_.asked_sent();
}

}  // namespace fleetmap::aggregator::node
