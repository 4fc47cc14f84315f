#include "aggregator/node/map_request_answerer.h"

#include <algorithm>
#include <string>

#include "aggregator/node/map_key.h"
#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {

MapRequestAnswerer::MapRequestAnswerer(const Aggregator& aggregator,
                                       const AggregatorNodeOptions& options,
                                       MapPublisher& publisher, NodeReporting report, double now_s)
    : aggregator_(aggregator),
      options_(options),
      publisher_(publisher),
      report_(report),
      requests_(options_.keyframe_min_interval_s),
      next_keyframe_s_(now_s + options_.keyframe_period_s) {}

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
    requests_.AddKeyframe(request.tiles);  // (a vehicle ahead of us: our state was lost)
  } else if (have < current) {
    const bool retained =
        store.Delta(static_cast<uint64_t>(have)).ok() && store.Delta(current - 1).ok();
    if (retained) {
      requests_.AddDeltas(static_cast<uint64_t>(have));
    } else {
      requests_.AddKeyframe({});
    }
  }  // have == current: the vehicle is up to date
}

void MapRequestAnswerer::Tick(double now_s) {
  if (options_.keyframe_period_s > 0 && now_s >= next_keyframe_s_) {
    publisher_.SendKeyframe(nullptr, now_s);
    publisher_.SendCandidates(now_s);  // for vehicles that joined since they last changed
    requests_.WholeKeyframeSent(now_s);
    next_keyframe_s_ = now_s + options_.keyframe_period_s;
  }
  SendRequested(now_s);
}

void MapRequestAnswerer::SendRequested(double now_s) {
  const RequestPlan plan = requests_.Take(now_s);
  const CurrentMapStore& store = aggregator_.store();
  if (plan.deltas_from) {
    for (uint64_t v = *plan.deltas_from; v < store.version(); ++v) {
      auto delta = store.Delta(v);
      if (!delta.ok()) {  // dropped meanwhile: a keyframe answers instead
        requests_.AddKeyframe({});
        break;
      }
      publisher_.SendDelta(*delta, now_s);
      ++report_.counters.deltas_resent;
    }
  }
  if (plan.full_keyframe) publisher_.SendKeyframe(nullptr, now_s);
  if (!plan.full_keyframe && !plan.keyframe_tiles.empty())
    publisher_.SendKeyframe(&plan.keyframe_tiles, now_s);
}

}  // namespace fleetmap::aggregator::node
