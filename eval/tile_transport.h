// What the aggregator process receives of a temporary map: the map cut into TEMPMAP tiles
// (core/codec/temp_map_tiles.h: int8 log-odds in steps of 0.05, the header fields) and put together
// again by the assembler. The in-process pipeline merges exactly this, so the evaluation
// scores the evidence that really travels over LCM (quantised log-odds, no trajectory), not
// the vehicle's float grid.
#pragma once

#include "core/map/temp_map.h"

namespace fleetmap::eval {

// DataLoss if the tiles do not reassemble (a defect of the tile code, not of the map).
core::Result<core::TempMap> AsReceived(const core::TempMap& map, int tile_size_cells = 64);

}  // namespace fleetmap::eval
