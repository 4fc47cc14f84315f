#include "core/codec/tile_delta.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace fleetmap::core {
namespace {

// Raw cell comparison, row by row: most tiles of a delta are untouched and this rules them
// out without packing them.
bool CellsDiffer(const OccupancyGrid& a, const OccupancyGrid& b, const CellWindow& w) {
  for (int y = w.y0; y < w.y0 + w.height; ++y) {
    const int64_t i = a.geometry().Index({w.x0, y});
    if (std::memcmp(a.cells().data() + i, b.cells().data() + i, sizeof(float) * w.width) != 0) {
      return true;
    }
  }
  return false;
}

}  // namespace

Status TileOptions::Validate() const {
  if (tile_size_cells < 4 || tile_size_cells > 4096) {
    return InvalidArgument("tile_size_cells must be in [4, 4096], got " +
                           std::to_string(tile_size_cells));
  }
  return OkStatus();
}

TileLayout::TileLayout(const GridGeometry& geometry, int tile_size_cells)
    : width_(geometry.width()),
      height_(geometry.height()),
      tile_size_(tile_size_cells),
      tiles_x_((geometry.width() + tile_size_cells - 1) / tile_size_cells),
      tiles_y_((geometry.height() + tile_size_cells - 1) / tile_size_cells) {
  assert(tile_size_cells > 0);
}

CellWindow TileLayout::Window(const TileIndex& t) const {
  const int x0 = t.tx * tile_size_, y0 = t.ty * tile_size_;
  return {x0, y0, std::min(tile_size_, width_ - x0), std::min(tile_size_, height_ - y0)};
}

std::vector<EncodedTile> EncodeChangedTiles(const OccupancyGrid& before, const OccupancyGrid& after,
                                            const TileOptions& options) {
  assert(before.geometry() == after.geometry());
  const TileLayout layout(after.geometry(), options.tile_size_cells);
  const CodecOptions& codec = options.codec;
  std::vector<EncodedTile> tiles;
  for (int i = 0; i < layout.num_tiles(); ++i) {
    const TileIndex t = layout.FromLinear(i);
    const CellWindow w = layout.Window(t);
    if (!CellsDiffer(before, after, w)) continue;
    // Compare in the packing's terms: a change below its resolution is no change.
    if (PackCells(before, w, codec.packing, codec.thresholds) ==
        PackCells(after, w, codec.packing, codec.thresholds)) {
      continue;
    }
    tiles.push_back({t, EncodeWindow(after, w, codec)});
  }
  return tiles;
}

std::vector<EncodedTile> EncodeAllTiles(const OccupancyGrid& grid, const TileOptions& options) {
  const TileLayout layout(grid.geometry(), options.tile_size_cells);
  std::vector<EncodedTile> tiles;
  tiles.reserve(static_cast<size_t>(layout.num_tiles()));
  for (int i = 0; i < layout.num_tiles(); ++i) {
    const TileIndex t = layout.FromLinear(i);
    tiles.push_back({t, EncodeWindow(grid, layout.Window(t), options.codec)});
  }
  return tiles;
}

Status ApplyTiles(const std::vector<EncodedTile>& tiles, int tile_size_cells, OccupancyGrid& grid) {
  const TileLayout layout(grid.geometry(), tile_size_cells);
  DecodeLimits limits;
  limits.max_cells = int64_t{tile_size_cells} * tile_size_cells;
  std::vector<DecodedFrame> decoded;
  decoded.reserve(tiles.size());
  for (const EncodedTile& tile : tiles) {
    const std::string where =
        "tile (" + std::to_string(tile.index.tx) + ", " + std::to_string(tile.index.ty) + ")";
    if (tile.index.tx < 0 || tile.index.ty < 0 || tile.index.tx >= layout.tiles_x() ||
        tile.index.ty >= layout.tiles_y()) {
      return OutOfRange(where + " lies outside the map's tile layout");
    }
    auto frame = DecodeFrame(tile.frame, limits);
    if (!frame.ok()) return frame.status().WithContext(where);
    if (!(frame->window == layout.Window(tile.index))) {
      return DataLoss(where + ": frame window does not match the tile");
    }
    decoded.push_back(std::move(frame).value());
  }
  for (const DecodedFrame& frame : decoded) {
    FLEETMAP_RETURN_IF_ERROR(ApplyFrame(frame, grid));  // cannot fail: windows checked above
  }
  return OkStatus();
}

size_t TotalFrameBytes(const std::vector<EncodedTile>& tiles) {
  size_t n = 0;
  for (const EncodedTile& t : tiles) n += t.frame.size();
  return n;
}

}  // namespace fleetmap::core
