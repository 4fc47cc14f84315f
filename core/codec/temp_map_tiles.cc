#include "core/codec/temp_map_tiles.h"

#include <cmath>

#include "core/odometry.h"

namespace fleetmap::core {

TileOptions TempMapTileOptions(int tile_size_cells) {
  TileOptions o;
  o.tile_size_cells = tile_size_cells;
  o.codec.packing = CellPacking::kLogOddsInt8;
  return o;
}

std::vector<TempMapTile> SplitTempMap(const TempMap& map, const TileOptions& options) {
  const std::vector<EncodedTile> encoded = EncodeAllTiles(map.grid, options);
  const GridGeometry& g = map.grid.geometry();
  std::vector<TempMapTile> tiles;
  for (size_t i = 0; i < encoded.size(); ++i) {
    TempMapTile t;
    t.vehicle_id = map.vehicle_id;
    t.sequence = map.sequence;
    t.index = static_cast<int32_t>(i);
    t.count = static_cast<int32_t>(encoded.size());
    t.anchor_in_map = map.anchor_in_map;
    t.grid_origin = map.grid.geometry().origin();
    t.anchor_covariance = map.anchor_covariance;
    t.resolution_m = g.resolution_m();
    t.width_cells = g.width();
    t.height_cells = g.height();
    t.start_s = map.start_s;
    t.end_s = map.end_s;
    t.tile = encoded[i].index;
    t.frame = encoded[i].frame;
    tiles.push_back(std::move(t));
  }
  return tiles;
}

Status AssemblerOptions::Validate() const {
  if (tile_size_cells < 4 || max_pending_maps < 1 || max_map_cells < 1 || max_tiles < 1) {
    return InvalidArgument("assembler options must be positive (tile_size_cells >= 4)");
  }
  return OkStatus();
}

TempMapAssembler::TempMapAssembler(const AssemblerOptions& options) : options_(options) {}

Status TempMapAssembler::CheckAlone(const TempMapTile& t) const {
  if (t.vehicle_id.empty()) return InvalidArgument("tile without a vehicle id");
  if (t.count < 1 || t.count > options_.max_tiles || t.index < 0 || t.index >= t.count) {
    return OutOfRange("tile " + std::to_string(t.index) + " of " + std::to_string(t.count) +
                      " is out of range");
  }
  const GridGeometry g(t.resolution_m, t.width_cells, t.height_cells, t.corner_in_map());
  FLEETMAP_RETURN_IF_ERROR(g.Validate().WithContext("temporary map header"));
  if (g.num_cells() > options_.max_map_cells) {
    return OutOfRange("temporary map of " + std::to_string(g.num_cells()) + " cells exceeds " +
                      std::to_string(options_.max_map_cells));
  }
  const TileLayout layout(g, options_.tile_size_cells);
  if (layout.num_tiles() != t.count) return DataLoss("tile count does not fit the map's size");
  // The position first: Linear() of a position far outside the layout overflows.
  if (t.tile.tx < 0 || t.tile.ty < 0 || t.tile.tx >= layout.tiles_x() ||
      t.tile.ty >= layout.tiles_y() || layout.Linear(t.tile) != t.index) {
    return DataLoss("tile position does not fit its index");
  }
  if (!std::isfinite(t.start_s) || !std::isfinite(t.end_s) || t.end_s < t.start_s) {
    return InvalidArgument("temporary map times are not finite or out of order");
  }
  if (t.anchor_covariance)
    FLEETMAP_RETURN_IF_ERROR(
        ValidatePoseCovariance(*t.anchor_covariance).WithContext("temporary map anchor"));
  return OkStatus();
}

namespace {
bool SamePose(const Pose2& a, const Pose2& b) {
  return a.x_m == b.x_m && a.y_m == b.y_m && a.theta_rad == b.theta_rad;
}
bool SameCovariance(const std::optional<Eigen::Matrix3d>& a,
                    const std::optional<Eigen::Matrix3d>& b) {
  return a.has_value() == b.has_value() && (!a || *a == *b);
}
}  // namespace

Status TempMapAssembler::CheckSameMap(const TempMapTile& a, const TempMapTile& b) {
  const bool same = a.count == b.count && a.resolution_m == b.resolution_m &&
                    a.width_cells == b.width_cells && a.height_cells == b.height_cells &&
                    SamePose(a.anchor_in_map, b.anchor_in_map) &&
                    SamePose(a.grid_origin, b.grid_origin) &&
                    SameCovariance(a.anchor_covariance, b.anchor_covariance) &&
                    a.start_s == b.start_s && a.end_s == b.end_s;
  return same ? OkStatus() : InvalidArgument("tile disagrees with the other tiles of its map");
}

Result<std::optional<TempMap>> TempMapAssembler::Add(const TempMapTile& tile) {
  FLEETMAP_RETURN_IF_ERROR(CheckAlone(tile));
  const GridGeometry g(tile.resolution_m, tile.width_cells, tile.height_cells);
  DecodeLimits limits;
  limits.max_cells = int64_t{options_.tile_size_cells} * options_.tile_size_cells;
  auto frame = DecodeFrame(tile.frame, limits);
  if (!frame.ok()) return frame.status().WithContext("tile " + std::to_string(tile.index));
  if (!(frame->window == TileLayout(g, options_.tile_size_cells).Window(tile.tile))) {
    return DataLoss("tile " + std::to_string(tile.index) + ": frame window does not fit the tile");
  }
  const auto key = std::make_pair(tile.vehicle_id, tile.sequence);
  auto it = pending_.find(key);
  if (it == pending_.end()) {
    if (static_cast<int>(pending_.size()) >= options_.max_pending_maps) {
      return OutOfRange("too many temporary maps being assembled");
    }
    it = pending_.emplace(key, Pending{tile, {}}).first;
    it->second.header.frame.clear();
  }
  FLEETMAP_RETURN_IF_ERROR(CheckSameMap(it->second.header, tile));
  it->second.frames.emplace(tile.index, std::move(frame).value());
  if (static_cast<int32_t>(it->second.frames.size()) < tile.count) return std::optional<TempMap>();
  TempMap map = Assemble(it->second);
  pending_.erase(it);
  return std::optional<TempMap>(std::move(map));
}

TempMap TempMapAssembler::Assemble(const Pending& p) const {
  const TempMapTile& h = p.header;
  TempMap map;
  map.vehicle_id = h.vehicle_id;
  map.sequence = h.sequence;
  map.anchor_in_map = h.anchor_in_map;
  map.anchor_covariance = h.anchor_covariance;
  map.grid =
      OccupancyGrid(GridGeometry(h.resolution_m, h.width_cells, h.height_cells, h.grid_origin));
  for (const auto& [index, frame] : p.frames) (void)ApplyFrame(frame, map.grid);  // checked
  map.start_s = h.start_s;
  map.end_s = h.end_s;
  return map;
}

std::vector<int32_t> TempMapAssembler::Received(const std::string& vehicle_id,
                                                int32_t sequence) const {
  std::vector<int32_t> out;
  auto it = pending_.find({vehicle_id, sequence});
  if (it != pending_.end())
    for (const auto& [index, frame] : it->second.frames) out.push_back(index);
  return out;
}

void TempMapAssembler::Drop(const std::string& vehicle_id, int32_t sequence) {
  pending_.erase({vehicle_id, sequence});
}

}  // namespace fleetmap::core
