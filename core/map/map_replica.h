// A vehicle's copy of the current map, kept up to date from the aggregator's tiles: keyframe
// tiles (each tile of the map as it was at some version) build it, deltas (the tiles that
// changed from v to v+1) advance it one version at a time, in order. The aggregator sends its
// keyframe tile by tile over seconds (a rolling keyframe), so the tiles of one keyframe may be
// of several versions: a tile of version h counts for the newest version V seen when the
// deltas from h to V are held (the delta's copy of the tile replaces it when the tile
// changed); a tile that cannot be brought to V is dropped and waits for its next copy. Nothing
// is applied half: a version becomes the map only when all its tiles are in. A missed delta
// (a version gap) shows in NeedsKeyframe() so that the vehicle asks for it, and tiles for
// other maps are refused.
#pragma once

#include <map>
#include <optional>
#include <vector>

#include "core/codec/tile_delta.h"

namespace fleetmap::core {

// One tile of a keyframe: the map's geometry travels with every tile.
struct KeyframeTile {
  int32_t version = 0;
  GridGeometry geometry;
  int32_t tile_size_cells = 64;
  int32_t index = 0, count = 0;
  TileIndex tile;
  std::vector<uint8_t> frame;
};

// One tile of the change from base_version to base_version + 1.
struct DeltaTile {
  int32_t base_version = 0;
  int32_t index = 0, count = 0;  // count 0: the version changed no cell
  TileIndex tile;
  std::vector<uint8_t> frame;
};

class MapReplica {
 public:
  explicit MapReplica(int max_buffered_versions = 16);

  // Starts from a map the vehicle already holds (the static map file, which is version 0 at
  // the aggregator), so that deltas from `version` on apply without waiting for a keyframe.
  // `tile_size_cells` is the tiling the aggregator's deltas use (deltas carry no geometry).
  // A keyframe of a newer version still replaces it.
  Status Seed(OccupancyGrid grid, int32_t version, int32_t tile_size_cells = 64);
  // Returns true when this tile completed a keyframe that is now the map.
  Result<bool> AddKeyframeTile(const KeyframeTile& tile);
  // Returns true when this tile completed one or more versions that are now applied.
  Result<bool> AddDeltaTile(const DeltaTile& tile);

  bool has_map() const { return map_.has_value(); }
  const OccupancyGrid& map() const { return *map_; }
  int32_t version() const { return version_; }
  // No map yet, or deltas are waiting for a version that was missed.
  bool NeedsKeyframe() const;
  // While a keyframe is being assembled: the linear indices of the tiles it still lacks,
  // ascending. Empty when none is (no tile received yet: the whole map is lacking).
  std::vector<int32_t> MissingKeyframeTiles() const;
  // Where the map changed since the last call: the tiles of the deltas applied since, or the
  // whole grid after a seed or a keyframe (every cell may differ from a map held before).
  // Empty when nothing changed.
  CellWindow TakeChanged();

 private:
  struct PendingVersion {
    int32_t count = 0;
    std::map<int32_t, EncodedTile> tiles;
  };
  // A keyframe tile with the version at which its cells hold.
  struct HeldTile {
    int32_t version = 0;
    EncodedTile tile;
  };
  void ApplyReadyDeltas();
  // Makes the assembled keyframe the map when every tile can be brought to its newest
  // version; drops the tiles that cannot (a delta between is missing). True when it did.
  Result<bool> CompleteKeyframe();

  int max_buffered_versions_;
  std::optional<OccupancyGrid> map_;
  int32_t version_ = -1;
  int32_t tile_size_cells_ = 64;
  std::map<int32_t, PendingVersion> deltas_;  // by base version
  CellWindow changed_;                        // the tiles of the deltas applied since TakeChanged
  bool whole_changed_ = false;                // a seed or a keyframe since TakeChanged
  std::optional<KeyframeTile> keyframe_header_;  // its version: the newest of its tiles
  std::map<int32_t, HeldTile> keyframe_tiles_;
};

}  // namespace fleetmap::core
