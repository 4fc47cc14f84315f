#include "core/map/map_replica.h"

#include <algorithm>
#include <iterator>

namespace fleetmap::core {
namespace {

bool SameLayout(const KeyframeTile& a, const KeyframeTile& b) {
  return a.geometry == b.geometry && a.tile_size_cells == b.tile_size_cells && a.count == b.count;
}

}  // namespace

MapReplica::MapReplica(int max_buffered_versions) : max_buffered_versions_(max_buffered_versions) {}

bool MapReplica::NeedsKeyframe() const {
  if (!map_) return true;
  return !deltas_.empty() && deltas_.begin()->first > version_;
}

CellWindow MapReplica::TakeChanged() {
  const CellWindow changed = !map_            ? CellWindow{}
                             : whole_changed_ ? map_->geometry().full_window()
                                              : changed_;
  changed_ = {};
  whole_changed_ = false;
  return changed;
}

Status MapReplica::Seed(OccupancyGrid grid, int32_t version, int32_t tile_size_cells) {
  FLEETMAP_RETURN_IF_ERROR(grid.geometry().Validate().WithContext("seed map"));
  TileOptions options;
  options.tile_size_cells = tile_size_cells;
  FLEETMAP_RETURN_IF_ERROR(options.Validate().WithContext("seed map"));
  if (version < 0) return InvalidArgument("seed map: version must be >= 0");
  map_ = std::move(grid);
  version_ = version;
  tile_size_cells_ = tile_size_cells;
  whole_changed_ = true;
  keyframe_header_.reset();
  keyframe_tiles_.clear();
  deltas_.erase(deltas_.begin(), deltas_.lower_bound(version_));
  ApplyReadyDeltas();
  return OkStatus();
}

Result<bool> MapReplica::AddKeyframeTile(const KeyframeTile& tile) {
  FLEETMAP_RETURN_IF_ERROR(tile.geometry.Validate().WithContext("keyframe"));
  TileOptions options;
  options.tile_size_cells = tile.tile_size_cells;
  FLEETMAP_RETURN_IF_ERROR(options.Validate().WithContext("keyframe"));
  const TileLayout layout(tile.geometry, tile.tile_size_cells);
  // The position before Linear(), which overflows for one far outside the layout.
  if (tile.count != layout.num_tiles() || tile.index < 0 || tile.index >= tile.count ||
      tile.tile.tx < 0 || tile.tile.ty < 0 || tile.tile.tx >= layout.tiles_x() ||
      tile.tile.ty >= layout.tiles_y() || layout.Linear(tile.tile) != tile.index) {
    return DataLoss("keyframe tile index or count does not fit the map");
  }
  if (map_ && tile.version <= version_) return false;  // we are already there
  if (keyframe_header_ && !SameLayout(*keyframe_header_, tile)) {
    if (tile.version < keyframe_header_->version) return false;  // a tile of an older map
    keyframe_header_.reset();  // the aggregator's map was replaced: start again
    keyframe_tiles_.clear();
  }
  if (!keyframe_header_) {
    keyframe_header_ = tile;
    keyframe_header_->frame.clear();
  }
  const bool newer = tile.version > keyframe_header_->version;
  keyframe_header_->version = std::max(keyframe_header_->version, tile.version);
  const auto held = keyframe_tiles_.find(tile.index);
  if (held == keyframe_tiles_.end() || held->second.version <= tile.version)
    keyframe_tiles_[tile.index] = HeldTile{tile.version, EncodedTile{tile.tile, tile.frame}};
  if (!map_ && newer) {
    // Tiles are cut from the aggregator's current map when sent: none still to come is older
    // than those held, so older deltas can never be needed.
    int32_t oldest = keyframe_header_->version;
    for (const auto& [i, t] : keyframe_tiles_) oldest = std::min(oldest, t.version);
    deltas_.erase(deltas_.begin(), deltas_.lower_bound(oldest));
  }
  return CompleteKeyframe();
}

Result<bool> MapReplica::CompleteKeyframe() {
  if (keyframe_header_ && map_ && keyframe_header_->version <= version_) {
    keyframe_header_.reset();  // the deltas asked for got there first
    keyframe_tiles_.clear();
  }
  if (!keyframe_header_ || static_cast<int32_t>(keyframe_tiles_.size()) < keyframe_header_->count)
    return false;
  const int32_t newest = keyframe_header_->version;
  bool all_current = true;
  for (auto it = keyframe_tiles_.begin(); it != keyframe_tiles_.end();) {
    HeldTile& held = it->second;
    bool lost = false;
    for (; held.version < newest; ++held.version) {
      const auto delta = deltas_.find(held.version);
      if (delta == deltas_.end()) {
        lost = true;  // missed: the tile waits for its next copy
        break;
      }
      const PendingVersion& p = delta->second;
      if (static_cast<int32_t>(p.tiles.size()) < p.count) break;  // its tiles still arrive
      const auto changed = p.tiles.find(it->first);
      if (changed != p.tiles.end()) held.tile = changed->second;
    }
    all_current = all_current && held.version == newest && !lost;
    it = lost ? keyframe_tiles_.erase(it) : std::next(it);
  }
  if (!all_current) return false;
  const KeyframeTile header = *keyframe_header_;
  OccupancyGrid grid(header.geometry);
  std::vector<EncodedTile> tiles;
  for (auto& [i, t] : keyframe_tiles_) tiles.push_back(std::move(t.tile));
  keyframe_tiles_.clear();
  keyframe_header_.reset();
  const Status applied = ApplyTiles(tiles, header.tile_size_cells, grid);
  if (!applied.ok()) return applied.WithContext("keyframe version " + std::to_string(newest));
  map_ = std::move(grid);
  version_ = newest;
  tile_size_cells_ = header.tile_size_cells;
  whole_changed_ = true;
  deltas_.erase(deltas_.begin(), deltas_.lower_bound(version_));  // older than the keyframe
  ApplyReadyDeltas();
  return map_.has_value();  // a corrupt buffered delta drops the map it completed
}

std::vector<int32_t> MapReplica::MissingKeyframeTiles() const {
  std::vector<int32_t> missing;
  if (!keyframe_header_) return missing;
  for (int32_t i = 0; i < keyframe_header_->count; ++i)
    if (!keyframe_tiles_.count(i)) missing.push_back(i);
  return missing;
}

Result<bool> MapReplica::AddDeltaTile(const DeltaTile& tile) {
  if (tile.count < 0 || (tile.count > 0 && (tile.index < 0 || tile.index >= tile.count))) {
    return DataLoss("delta tile index or count out of range");
  }
  if (map_ && tile.base_version < version_) return false;  // old news
  if (!deltas_.count(tile.base_version) &&
      static_cast<int>(deltas_.size()) >= max_buffered_versions_) {
    return OutOfRange("too many versions waiting; a keyframe is needed");
  }
  PendingVersion& p = deltas_[tile.base_version];
  if (!p.tiles.empty() && p.count != tile.count) return DataLoss("delta tile count disagrees");
  p.count = tile.count;
  if (tile.count > 0) p.tiles[tile.index] = EncodedTile{tile.tile, tile.frame};
  const int32_t before = version_;
  if (map_) ApplyReadyDeltas();
  // The last tile of a delta a keyframe being assembled waited for.
  if (NeedsKeyframe() && keyframe_header_) {
    auto completed = CompleteKeyframe();
    if (!completed.ok()) return completed;
  }
  return map_.has_value() && version_ != before;  // not when a corrupt delta dropped the map
}

void MapReplica::ApplyReadyDeltas() {
  for (auto it = deltas_.find(version_); it != deltas_.end(); it = deltas_.find(version_)) {
    PendingVersion& p = it->second;
    if (static_cast<int32_t>(p.tiles.size()) < p.count) return;  // still waiting
    std::vector<EncodedTile> tiles;
    for (auto& [i, t] : p.tiles) tiles.push_back(std::move(t));
    const Status s = ApplyTiles(tiles, tile_size_cells_, *map_);
    deltas_.erase(it);
    if (!s.ok()) {
      // A corrupt delta cannot be applied: drop the map so that a keyframe is requested.
      map_.reset();
      version_ = -1;
      return;
    }
    const TileLayout layout(map_->geometry(), tile_size_cells_);
    for (const EncodedTile& t : tiles) changed_ = Union(changed_, layout.Window(t.index));
    ++version_;
  }
}

}  // namespace fleetmap::core
