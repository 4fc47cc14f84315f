#include "vehicle_agent/node/map_updates.h"

#include <string>

#include "lcmtypes/channels.h"

namespace fleetmap::vehicle_agent::node {

MapUpdates::MapUpdates(const MapFollowerOptions& options, CauseLog* log,
                       AgentNodeCounters* counters)
    : log_(log), counters_(counters), follower_(options) {}

core::Status MapUpdates::Seed(core::OccupancyGrid map, int32_t version) {
  FLEETMAP_RETURN_IF_ERROR(follower_.Seed(std::move(map), version));
  due_ = true;
  return core::OkStatus();
}

void MapUpdates::OnDeltaTile(const core::DeltaTile& tile) {
  Tile(lcmtypes::kMapDeltaChannel, follower_.OnDeltaTile(tile));
}

void MapUpdates::OnKeyframeTile(const core::KeyframeTile& tile) {
  const core::Result<bool> added = follower_.OnKeyframeTile(tile);
  // A keyframe completes rarely (no map yet, a gap) and is worth a line: a large map takes
  // seconds to arrive, and more to be put in use.
  if (added.ok() && *added)
    log_->Info("map version " + std::to_string(follower_.version()) + " held (" +
               std::to_string(tile.count) + " keyframe tiles)");
  Tile(lcmtypes::kMapKeyframeChannel, added);
}

void MapUpdates::Tile(const char* channel, const core::Result<bool>& added) {
  if (!added.ok()) {
    log_->Once(channel + std::string(": ") + core::StatusCodeName(added.status().code()),
               channel + std::string(": tile refused: ") + added.status().ToString());
    return;
  }
  due_ |= *added;
}

void MapUpdates::OnRemoteVersion(int32_t version, double now_s) {
  follower_.OnRemoteVersion(version, now_s);
}

bool MapUpdates::Apply(AgentPipeline& pipeline) {
  if (!due_) return false;
  due_ = false;
  // Due means a tile completed a version (or the static map came in), not a version number
  // above the one in use: after an aggregator restart a new map may carry a number held before.
  if (!follower_.has_map()) return false;
  // The vehicle's scan models follow the delta's tiles rather than the whole map: a new
  // version of a large building must not stall the scan loop.
  const core::CellWindow changed = follower_.TakeChanged();
  const core::Status s = in_use_ && !whole_next_
                             ? pipeline.UpdateMap(follower_.map(), follower_.version(), changed)
                             : pipeline.SetMap(follower_.map(), follower_.version());
  whole_next_ = !s.ok();  // what changed is lost with a refused version
  if (!s.ok()) {
    ++counters_->map_swaps_failed;
    log_->Once("map swap",
               "map version " + std::to_string(follower_.version()) + " not used: " + s.ToString());
    return false;
  }
  const bool first = !in_use_;
  in_use_ = true;
  version_in_use_ = follower_.version();
  log_->Info("map version " + std::to_string(version_in_use_) + " in use");
  return first;
}

std::optional<int32_t> MapUpdates::RequestDue(double now_s) {
  const int64_t resets = follower_.counters().resets;
  const std::optional<int32_t> have = follower_.RequestDue(now_s);
  if (follower_.counters().resets != resets) {
    log_->Warning(
        "the aggregator's map versions went back below " + std::to_string(version_in_use_) +
        " (restarted without its state?): asking for its map, localizing on ours meanwhile");
  }
  return have;
}

}  // namespace fleetmap::vehicle_agent::node
