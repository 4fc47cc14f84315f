// Brings vehicles that missed versions of the current map up to date. A MAP_REQUEST names
// the version the vehicle has, or the tiles it lacks: it is answered with the deltas since
// that version while the store retains all of them, otherwise with keyframe tiles (all, or
// the tiles listed). Requests are coalesced and answered at the next Tick, so that many
// vehicles asking at once (after a restart, or a delta everyone missed) cost one answer:
// deltas once from the oldest version asked for, each keyframe tile once however many asked
// (keyframe_schedule.h). Unasked, a rolling keyframe sends every tile in turn, one round per
// keyframe_period_s, and the candidates go out every keyframe_period_s, for vehicles that
// missed everything; it takes at most keyframe_share of the downlink's budget, so that on a
// large map a round lasts longer rather than keeping the channel full. Keyframe tiles can
// wait: they go only while the downlink has room (MapPublisher::room_bytes), after
// acknowledgements and deltas, which never wait for them; asked tiles before rolling ones.
// Owns the waiting requests and the keyframe schedule; reads the current map.
#pragma once

#include <optional>

#include "aggregator/aggregator.h"
#include "aggregator/node/keyframe_schedule.h"
#include "aggregator/node/map_publisher.h"
#include "aggregator/node/node_options.h"
#include "aggregator/node/node_reporting.h"
#include "core/codec/send_pacer.h"
#include "fleetmap/map_request_t.hpp"

namespace fleetmap::aggregator::node {

class MapRequestAnswerer {
 public:
  // `aggregator` and `publisher` outlive this; the rolling keyframe starts at `now_s`, the
  // first candidates go keyframe_period_s after.
  MapRequestAnswerer(const Aggregator& aggregator, const AggregatorNodeOptions& options,
                     MapPublisher& publisher, NodeReporting report, double now_s);
  MapRequestAnswerer(const MapRequestAnswerer&) = delete;
  MapRequestAnswerer& operator=(const MapRequestAnswerer&) = delete;

  // The payload of a MAP_REQUEST: checked against the current map, then queued.
  void OnRequest(const void* data, int size);
  // The deltas asked for, the candidates when due, then keyframe tiles (asked ones first)
  // while the downlink has room.
  void Tick(double now_s);

  // Asked keyframe tiles wait: they go at the downlink's whole budget, so the caller should
  // Tick again within milliseconds. (The rolling keyframe's quarter of it goes in the room of
  // ordinary ticks.)
  bool sending() const { return schedule_.asked() > 0; }
  // Asked keyframe tiles not yet sent.
  int32_t tiles_waiting() const { return schedule_.asked(); }

 private:
  // False (refused, counted, logged) for a version or tile the current map cannot have.
  bool Possible(const fleetmap::map_request_t& request);
  void Queue(const fleetmap::map_request_t& request);
  void SendDeltas(double now_s);
  void SendKeyframeTiles(double now_s);

  const Aggregator& aggregator_;
  const AggregatorNodeOptions options_;
  MapPublisher& publisher_;
  NodeReporting report_;
  std::optional<uint64_t> deltas_from_;  // resend every version from here to the current
  KeyframeSchedule schedule_;
  double next_candidates_s_;
  core::SendPacer rolling_share_;  // the rolling keyframe's share of the budget
};

}  // namespace fleetmap::aggregator::node
