// The map the node localizes on: the aggregator's versions as their tiles complete them
// (MapFollower), handed to the pipeline between scans without stopping it, and when to ask
// the aggregator to catch up (MAP_REQUEST). Tiles come in decoded; refused ones are logged
// once per cause and counted by the follower.
#pragma once

#include <cstdint>
#include <optional>

#include "vehicle_agent/agent_pipeline.h"
#include "vehicle_agent/node/agent_counters.h"
#include "vehicle_agent/node/map_follower.h"
#include "vehicle_agent/node/node_io.h"

namespace fleetmap::vehicle_agent::node {

class MapUpdates {
 public:
  // `log` and `counters` (map_swaps_failed) outlive the updates.
  MapUpdates(const MapFollowerOptions& options, CauseLog* log, AgentNodeCounters* counters);

  // Starts from the static map file at `version`; the pipeline takes it at the next Apply.
  core::Status Seed(core::OccupancyGrid map, int32_t version);
  // A tile of MAP_DELTA or MAP_KEYFRAME; one that completes a version makes it due.
  void OnDeltaTile(const core::DeltaTile& tile);
  void OnKeyframeTile(const core::KeyframeTile& tile);
  // The version the aggregator's heartbeat says it holds.
  void OnRemoteVersion(int32_t version, double now_s);

  // Hands a version completed since the last call to `pipeline` (nothing when none is due).
  // Returns true when it is the first map the pipeline took; a map the pipeline refuses is
  // counted and logged, and the one in use stays.
  bool Apply(AgentPipeline& pipeline);
  // have_version for a MAP_REQUEST to send now, or nothing (MapFollower::RequestDue).
  std::optional<int32_t> RequestDue(double now_s);
  // The keyframe tiles that request names (MapFollower::request_tiles).
  const std::vector<int32_t>& request_tiles() const { return follower_.request_tiles(); }

  // Whether the pipeline has a map, and its version (-1: none yet).
  bool in_use() const { return in_use_; }
  int32_t version_in_use() const { return version_in_use_; }
  const MapFollower& follower() const { return follower_; }

 private:
  void Tile(const char* channel, const core::Result<bool>& added);

  CauseLog* const log_;
  AgentNodeCounters* const counters_;
  MapFollower follower_;
  bool due_ = false;  // the follower has a version the pipeline does not
  bool in_use_ = false;
  bool whole_next_ = false;  // the last version was refused: the next starts afresh
  int32_t version_in_use_ = -1;
};

}  // namespace fleetmap::vehicle_agent::node
