#include "eval/tile_transport.h"

#include "core/codec/temp_map_tiles.h"

namespace fleetmap::eval {

core::Result<core::TempMap> AsReceived(const core::TempMap& map, int tile_size_cells) {
  core::AssemblerOptions options;
  options.tile_size_cells = tile_size_cells;
  core::TempMapAssembler assembler(options);
  for (const core::TempMapTile& tile :
       core::SplitTempMap(map, core::TempMapTileOptions(tile_size_cells))) {
    auto assembled = assembler.Add(tile);
    if (!assembled.ok()) return assembled.status().WithContext("temporary map tiles");
    if (*assembled) return std::move(**assembled);
  }
  return core::DataLoss("temporary map tiles did not reassemble");
}

}  // namespace fleetmap::eval
