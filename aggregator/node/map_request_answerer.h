// Brings vehicles that missed versions of the current map up to date. A MAP_REQUEST names
// the version the vehicle has, or the tiles it lacks: it is answered with the deltas since
// that version while the store retains all of them, otherwise with a keyframe (whole, or the
// tiles listed). Requests are coalesced (request_queue.h) and answered at the next Tick, so
// that many vehicles asking at once (after a restart, or a delta everyone missed) cost one
// answer. Unasked, a whole keyframe and the candidates go out every keyframe_period_s for
// vehicles that missed everything; that keyframe also answers every keyframe request waiting.
// Owns the waiting requests and the periodic keyframe's time; reads the current map.
#pragma once

#include "aggregator/aggregator.h"
#include "aggregator/node/map_publisher.h"
#include "aggregator/node/node_options.h"
#include "aggregator/node/node_reporting.h"
#include "aggregator/node/request_queue.h"
#include "fleetmap/map_request_t.hpp"

namespace fleetmap::aggregator::node {

class MapRequestAnswerer {
 public:
  // `aggregator` and `publisher` outlive this; the first periodic keyframe is due
  // keyframe_period_s after `now_s`.
  MapRequestAnswerer(const Aggregator& aggregator, const AggregatorNodeOptions& options,
                     MapPublisher& publisher, NodeReporting report, double now_s);
  MapRequestAnswerer(const MapRequestAnswerer&) = delete;
  MapRequestAnswerer& operator=(const MapRequestAnswerer&) = delete;

  // The payload of a MAP_REQUEST: checked against the current map, then queued.
  void OnRequest(const void* data, int size);
  // The periodic keyframe when due, then the answers to the requests waiting.
  void Tick(double now_s);

  // A keyframe request waits (for keyframe_min_interval_s to pass).
  bool keyframe_waiting() const { return requests_.keyframe_waiting(); }

 private:
  // False (refused, counted, logged) for a version or tile the current map cannot have.
  bool Possible(const fleetmap::map_request_t& request);
  void Queue(const fleetmap::map_request_t& request);
  void SendRequested(double now_s);

  const Aggregator& aggregator_;
  const AggregatorNodeOptions options_;
  MapPublisher& publisher_;
  NodeReporting report_;
  RequestQueue requests_;
  double next_keyframe_s_;
};

}  // namespace fleetmap::aggregator::node
