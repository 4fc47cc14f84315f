// Which uplink messages the aggregator node reads at all. Checked cheapest first: the
// payload's size, before anything is decoded (limits.max_received_bytes), then the channel,
// then the fleet key's signature (auth/verifier.h: a vehicle's channel must be signed by that
// vehicle, MAP_REQUEST by any member of the fleet). What passes is handed on by kind, as the
// signed payload; anything else is counted by cause, logged once, and goes no further.
// Owns the verifier and its counters.
#pragma once

#include <optional>
#include <string>

#include "aggregator/node/node_options.h"
#include "aggregator/node/node_reporting.h"
#include "auth/verifier.h"

namespace fleetmap::aggregator::node {

enum class UplinkKind {
  kTempMapTile,     // TEMPMAP_<vehicle>
  kCandidatesFree,  // CANDIDATES_FREE_<vehicle>
  kCandidatesHeld,  // CANDIDATES_HELD_<vehicle>
  kMapRequest,      // MAP_REQUEST
};

struct UplinkMessage {
  UplinkKind kind = UplinkKind::kTempMapTile;
  const void* data = nullptr;  // the payload without its authentication trailer
  int size = 0;
};

class UplinkGate {
 public:
  UplinkGate(const AggregatorNodeOptions& options, NodeReporting report);

  // One message as received; nothing when it is refused or not for the aggregator. The
  // result points into `data`.
  std::optional<UplinkMessage> Open(const std::string& channel, const void* data, int size);

  const auth::Verifier& verifier() const { return verifier_; }

 private:
  bool PayloadAllowed(const std::string& channel, const void* data, int size);
  std::optional<UplinkKind> KindOf(const std::string& channel);

  const AggregatorNodeOptions options_;
  NodeReporting report_;
  auth::Verifier verifier_;
};

}  // namespace fleetmap::aggregator::node
