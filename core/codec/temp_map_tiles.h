// A temporary map as it travels: cut into tiles of a few KB (one lost UDP packet loses a
// whole LCM message), each carrying the map's header so that any tile can be checked alone,
// and put together again on the server. The assembler is bounded: a vehicle cannot make it
// hold more maps or cells than its limits, and inconsistent tiles are refused with a reason.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/codec/tile_delta.h"
#include "core/map/temp_map.h"

namespace fleetmap::core {

struct TempMapTile {
  std::string vehicle_id;
  int32_t sequence = 0;
  int32_t index = 0;  // 0 .. count - 1
  int32_t count = 0;
  // The aggregator turns a map about its anchor: both travel, not only the placed corner.
  Pose2 anchor_in_map;  // localized vehicle pose where the map was started
  Pose2 grid_origin;    // the grid's cell (0, 0) corner in the map's frame T
  std::optional<Eigen::Matrix3d> anchor_covariance;  // TempMap::anchor_covariance
  Pose2 corner_in_map() const { return anchor_in_map * grid_origin; }
  double resolution_m = 0.0;
  int32_t width_cells = 0, height_cells = 0;  // the whole temporary map
  double start_s = 0.0, end_s = 0.0;
  TileIndex tile;              // position in the map's tile lattice
  std::vector<uint8_t> frame;  // codec frame of the tile's window (log-odds, int8)
};

// Temporary maps keep their evidence: int8 log-odds, zstd.
TileOptions TempMapTileOptions(int tile_size_cells = 64);

std::vector<TempMapTile> SplitTempMap(const TempMap& map,
                                      const TileOptions& options = TempMapTileOptions());

struct AssemblerOptions {
  int tile_size_cells = 64;
  int max_pending_maps = 32;           // maps being assembled at once, all vehicles
  int64_t max_map_cells = 16'000'000;  // 200 m x 200 m at 5 cm
  int max_tiles = 4096;
  Status Validate() const;
};

class TempMapAssembler {
 public:
  explicit TempMapAssembler(const AssemblerOptions& options = {});

  // Adds one tile. Returns the whole map once its last tile is in (and forgets it), nothing
  // while tiles are missing, an error for a tile that is malformed or disagrees with the
  // tiles of the same map before it (those are kept). A repeated tile is accepted quietly.
  Result<std::optional<TempMap>> Add(const TempMapTile& tile);
  // Indices of the tiles received so far of one map (for the acknowledgement).
  std::vector<int32_t> Received(const std::string& vehicle_id, int32_t sequence) const;
  void Drop(const std::string& vehicle_id, int32_t sequence);
  size_t pending() const { return pending_.size(); }

 private:
  struct Pending {
    TempMapTile header;  // the first tile's header fields
    std::map<int32_t, DecodedFrame> frames;
  };
  Status CheckAlone(const TempMapTile& tile) const;
  static Status CheckSameMap(const TempMapTile& a, const TempMapTile& b);
  TempMap Assemble(const Pending& p) const;

  AssemblerOptions options_;
  std::map<std::pair<std::string, int32_t>, Pending> pending_;
};

}  // namespace fleetmap::core
