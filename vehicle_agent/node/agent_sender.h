// Everything the agent sends, built from what the node hands over: each message signed as the
// vehicle (auth/signer.h; the identity trailer without a fleet key) and stamped with the
// node's clock carried to wall time (AgentNodeOptions::utime_offset_s). A message the
// transport refuses is counted and logged once per channel, and the node goes on.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "auth/signer.h"
#include "core/codec/temp_map_tiles.h"
#include "vehicle_agent/agent_pipeline.h"
#include "vehicle_agent/node/agent_counters.h"
#include "vehicle_agent/node/agent_node_options.h"
#include "vehicle_agent/node/node_io.h"

namespace fleetmap::vehicle_agent::node {

class AgentSender {
 public:
  // `publisher`, `log` and `counters` (publish_failures, seen_free_reports, held_reports)
  // outlive the sender. Signed sequence numbers start from the wall clock now.
  AgentSender(const AgentNodeOptions& options, Publisher* publisher, CauseLog* log,
              AgentNodeCounters* counters);

  // POSE_<id> and DIVERGENCE_<id> of one localized scan, on options.pose_link.
  // `tempmap_sequence`: the temporary map being built, or the last one.
  void SendStep(const core::LaserScan& scan, const AgentStep& step, int32_t tempmap_sequence);
  // TEMPMAP_<id>, one message per tile.
  void SendTiles(const std::vector<core::TempMapTile>& tiles, double now_s);
  // MAP_REQUEST with the version held (-1: none) and the keyframe tiles lacked (none: all).
  void SendMapRequest(int32_t have_version, const std::vector<int32_t>& tiles, double now_s);
  // CANDIDATES_FREE_<id>, then CANDIDATES_HELD_<id>: as many messages as the cells need
  // (none for no cells).
  void SendCandidates(const CandidatesSeenFree& seen, const CandidatesHeld& held,
                      int32_t map_version, double now_s);
  // STATUS_agent_<id>.
  void SendStatus(int32_t map_version, const std::string& state, const NamedCounters& counters,
                  bool authenticated, double now_s);

  // The utime of a message sent at `now_s` (the node's clock).
  int64_t Utime(double now_s) const;

 private:
  template <typename T>
  void Send(Link link, const std::string& channel, const T& message);

  const std::string vehicle_id_;
  const std::string software_version_;
  const Link pose_link_;
  const double utime_offset_s_;
  Publisher* const publisher_;
  CauseLog* const log_;
  AgentNodeCounters* const counters_;
  auth::Signer signer_;
};

}  // namespace fleetmap::vehicle_agent::node
