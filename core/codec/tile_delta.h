// A grid cut into square tiles, each encoded as its own codec frame: the unit in which maps
// travel over LCM. One lost UDP packet loses a whole LCM message, so a map goes as many small
// messages that are each useful alone (docs/channels.md, "What LCM needs"). A delta is the set of
// tiles whose packed cells differ between two grids; a keyframe is every tile.
#pragma once

#include <vector>

#include "core/codec/map_codec.h"

namespace fleetmap::core {

struct TileOptions {
  int tile_size_cells = 64;  // side of a square tile; 64 x 64 at 2 bits is 1 KB before zstd
  CodecOptions codec;
  Status Validate() const;
};

struct TileIndex {
  int tx = 0;  // tile column, from the grid origin
  int ty = 0;  // tile row
  bool operator==(const TileIndex& o) const { return tx == o.tx && ty == o.ty; }
};

// How a geometry is cut into tiles; edge tiles are clipped to the grid.
class TileLayout {
 public:
  TileLayout(const GridGeometry& geometry, int tile_size_cells);
  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }
  int num_tiles() const { return tiles_x_ * tiles_y_; }
  int Linear(const TileIndex& t) const { return t.ty * tiles_x_ + t.tx; }
  TileIndex FromLinear(int i) const { return {i % tiles_x_, i / tiles_x_}; }
  CellWindow Window(const TileIndex& t) const;

 private:
  int width_, height_, tile_size_, tiles_x_, tiles_y_;
};

struct EncodedTile {
  TileIndex index;
  std::vector<uint8_t> frame;  // a codec frame of the tile's window
};

// Tiles of `after` whose packed cells differ from `before` (same geometry required).
std::vector<EncodedTile> EncodeChangedTiles(const OccupancyGrid& before, const OccupancyGrid& after,
                                            const TileOptions& options = {});
// Every tile of `grid`: a keyframe.
std::vector<EncodedTile> EncodeAllTiles(const OccupancyGrid& grid, const TileOptions& options = {});

// Decodes every tile and checks each against the tile layout of `grid` before writing any:
// either all tiles are applied or none (the grid is untouched on error).
Status ApplyTiles(const std::vector<EncodedTile>& tiles, int tile_size_cells, OccupancyGrid& grid);

// Total bytes of the tiles' frames.
size_t TotalFrameBytes(const std::vector<EncodedTile>& tiles);

}  // namespace fleetmap::core
