// What the agent counts, and the flat (name, value) list STATUS_agent_<id> carries: the
// node's own counters, the input queue's, the outbox's, the map follower's and the
// localizer's bad-input counters, each name saying its unit (all are counts).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "vehicle_agent/localization/localizer.h"
#include "vehicle_agent/node/input_queue.h"
#include "vehicle_agent/node/map_follower.h"
#include "vehicle_agent/tempmap_outbox.h"

namespace fleetmap::vehicle_agent::node {

struct AgentNodeCounters {
  int64_t messages = 0;            // received on the subscribed channels
  int64_t malformed_messages = 0;  // did not decode, or failed validation
  int64_t wrong_vehicle = 0;       // on our channel but naming another vehicle
  int64_t scans = 0;               // localized
  int64_t scans_waiting_for_map = 0;
  int64_t scans_waiting_for_pose = 0;  // kFirstExternal before the first EXTPOSE
  int64_t odometry = 0;
  int64_t external_poses = 0;
  int64_t tempmaps_closed = 0;
  int64_t acks = 0;  // TEMPMAP_ACKs for this vehicle
  int64_t maps_merged = 0, maps_rejected = 0, maps_duplicate = 0;
  int64_t map_swaps_failed = 0;  // the pipeline refused a map version
  int64_t publish_failures = 0;
  int64_t auth_refused = 0;           // downlink messages the verifier refused (by cause: auth_*)
  int64_t seen_free_reports = 0;      // CANDIDATES_FREE_<id> messages sent
  int64_t held_reports = 0;           // CANDIDATES_HELD_<id> messages sent
  int64_t starts_from_last_pose = 0;  // the kept pose held at start (pose_store.h)
  int64_t lost = 0;                   // 1 while the localizer finds the vehicle lost, else 0
  int64_t tempmaps_dropped_lost = 0;  // being built when the vehicle relocalized: not sent
};

using NamedCounters = std::vector<std::pair<std::string, int64_t>>;

NamedCounters CollectCounters(const AgentNodeCounters& node, const InputQueue& queue,
                              const OutboxCounters& outbox, const MapFollowerCounters& map,
                              const LocalizerCounters& localizer);

// The value of `name` in `counters`, or -1.
int64_t CounterValue(const NamedCounters& counters, const std::string& name);

}  // namespace fleetmap::vehicle_agent::node
