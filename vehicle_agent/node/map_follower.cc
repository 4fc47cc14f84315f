#include "vehicle_agent/node/map_follower.h"

#include <algorithm>

namespace fleetmap::vehicle_agent::node {

core::Status MapFollowerOptions::Validate() const {
  if (tile_size_cells < 4) return core::InvalidArgument("map.tile_size_cells must be >= 4");
  if (!(request_period_s > 0.0))
    return core::InvalidArgument("rates.map_request_period_s must be > 0");
  if (max_buffered_versions < 1)
    return core::InvalidArgument("map.max_buffered_versions must be >= 1");
  if (max_request_tiles < 0) return core::InvalidArgument("map.max_request_tiles must be >= 0");
  return core::OkStatus();
}

MapFollower::MapFollower(const MapFollowerOptions& options)
    : options_(options), replica_(options.max_buffered_versions) {}

core::Status MapFollower::Seed(core::OccupancyGrid map, int32_t version) {
  const core::GridGeometry geometry = map.geometry();
  FLEETMAP_RETURN_IF_ERROR(replica_.Seed(std::move(map), version, options_.tile_size_cells));
  geometry_ = geometry;
  return core::OkStatus();
}

core::Result<bool> MapFollower::Counted(core::Result<bool> result, int64_t& accepted,
                                        int32_t version_before) {
  if (!result.ok()) {
    ++counters_.refused_tiles;
    return result;
  }
  ++accepted;
  // A keyframe is one version that became the map; one delta can complete several buffered.
  if (*result)
    counters_.versions_applied +=
        version_before < 0 ? 1 : std::max<int64_t>(1, replica_.version() - version_before);
  return result;
}

core::Result<bool> MapFollower::OnKeyframeTile(const core::KeyframeTile& tile) {
  if (geometry_ && !(tile.geometry == *geometry_)) {
    ++counters_.wrong_geometry_tiles;
    return core::FailedPrecondition(
        "keyframe of another map geometry (" + std::to_string(tile.geometry.width()) + " x " +
        std::to_string(tile.geometry.height()) + " cells at " +
        std::to_string(tile.geometry.resolution_m()) + " m, ours " +
        std::to_string(geometry_->width()) + " x " + std::to_string(geometry_->height()) + ")");
  }
  if (replica_.has_map() && tile.version <= replica_.version()) {
    ++counters_.stale_tiles;
    return false;
  }
  core::Result<bool> r = Counted(replica_.AddKeyframeTile(tile), counters_.keyframe_tiles, -1);
  if (r.ok() && *r) geometry_ = tile.geometry;
  return r;
}

core::Result<bool> MapFollower::OnDeltaTile(const core::DeltaTile& tile) {
  if (replica_.has_map() && tile.base_version < replica_.version()) {
    ++counters_.stale_tiles;
    return false;
  }
  const int32_t before = replica_.has_map() ? replica_.version() : -1;
  return Counted(replica_.AddDeltaTile(tile), counters_.delta_tiles, before);
}

void MapFollower::OnRemoteVersion(int32_t version, double now_s) {
  if (version > remote_version_ && version > replica_.version()) remote_ahead_since_s_ = now_s;
  const bool behind = replica_.has_map() && version < replica_.version();
  if (behind && !remote_behind_) remote_behind_since_s_ = now_s;
  remote_behind_ = behind;
  remote_version_ = version;
}

bool MapFollower::WantsRequest(double now_s) const {
  if (!asked_once_) return true;              // catch up at start, or the first ask
  if (replica_.NeedsKeyframe()) return true;  // no map yet, or a version gap
  return remote_version_ > replica_.version() &&
         now_s - remote_ahead_since_s_ >= options_.request_period_s;
}

std::optional<int32_t> MapFollower::RequestDue(double now_s) {
  // Two periods, so that a heartbeat overtaken by the delta it announces is no restart.
  if (remote_behind_ && now_s - remote_behind_since_s_ >= 2 * options_.request_period_s) {
    replica_ = core::MapReplica(options_.max_buffered_versions);
    remote_behind_ = false;
    asked_once_ = false;
    last_request_s_ = -std::numeric_limits<double>::infinity();
    ++counters_.resets;
  }
  if (!WantsRequest(now_s)) return std::nullopt;
  // A keyframe is a hundred tiles: ask once per period, whatever triggered it.
  if (now_s - last_request_s_ < options_.request_period_s) return std::nullopt;
  last_request_s_ = now_s;
  std::vector<int32_t> missing;
  if (!replica_.has_map()) missing = replica_.MissingKeyframeTiles();
  const bool listed =
      !missing.empty() && missing.size() <= static_cast<size_t>(options_.max_request_tiles);
  // The whole map asked for and keyframe tiles came since: the answer (or the rolling
  // keyframe) is arriving, and asking again would queue every tile once more.
  const bool arriving = asked_once_ && !replica_.has_map() && !listed &&
                        counters_.keyframe_tiles > keyframe_tiles_at_last_request_;
  keyframe_tiles_at_last_request_ = counters_.keyframe_tiles;
  if (arriving) return std::nullopt;
  asked_once_ = true;
  ++counters_.requests;
  request_tiles_.clear();
  if (listed) request_tiles_ = std::move(missing);
  return replica_.has_map() ? replica_.version() : -1;
}

}  // namespace fleetmap::vehicle_agent::node
