// The input format of tile_delta_fuzz, shared with the seed writer: a grid layout and a list
// of tiles as ApplyTiles takes them.
//   byte 0  tile size:   4 + b % 61 cells
//   byte 1  grid width:  1 + b cells
//   byte 2  grid height: 1 + b cells
//   then per tile: tile column (u8), tile row (u8), one codec frame, whose own payload size
//   field (header bytes 28..31) says where it ends; a frame cut short by the end of the input
//   ends there.
#pragma once

#include <cstdint>
#include <vector>

#include "core/codec/map_codec.h"
#include "core/codec/tile_delta.h"

namespace fleetmap::fuzz {

struct TileListInput {
  int tile_size_cells = 4;
  int width_cells = 1, height_cells = 1;
  std::vector<core::EncodedTile> tiles;
};

inline TileListInput ReadTileList(const uint8_t* data, size_t size) {
  TileListInput in;
  if (size < 3) return in;
  in.tile_size_cells = 4 + data[0] % 61;
  in.width_cells = 1 + data[1];
  in.height_cells = 1 + data[2];
  size_t pos = 3;
  while (size - pos >= 2) {
    core::EncodedTile tile;
    tile.index = {data[pos], data[pos + 1]};
    pos += 2;
    size_t n = size - pos;
    if (n >= core::kCodecHeaderBytes) {
      const uint8_t* p = data + pos + 28;
      const size_t payload =
          size_t{p[0]} | size_t{p[1]} << 8 | size_t{p[2]} << 16 | size_t{p[3]} << 24;
      const size_t whole = core::kCodecHeaderBytes + payload + core::kCodecTrailerBytes;
      if (whole < n) n = whole;
    }
    tile.frame.assign(data + pos, data + pos + n);
    pos += n;
    in.tiles.push_back(std::move(tile));
  }
  return in;
}

// Tiles of a grid of at most 256 x 256 cells, cut at `tile_size_cells` (4..64).
inline std::vector<uint8_t> WriteTileList(int tile_size_cells, int width_cells, int height_cells,
                                          const std::vector<core::EncodedTile>& tiles) {
  std::vector<uint8_t> out = {static_cast<uint8_t>(tile_size_cells - 4),
                              static_cast<uint8_t>(width_cells - 1),
                              static_cast<uint8_t>(height_cells - 1)};
  for (const core::EncodedTile& t : tiles) {
    out.push_back(static_cast<uint8_t>(t.index.tx));
    out.push_back(static_cast<uint8_t>(t.index.ty));
    out.insert(out.end(), t.frame.begin(), t.frame.end());
  }
  return out;
}

}  // namespace fleetmap::fuzz
