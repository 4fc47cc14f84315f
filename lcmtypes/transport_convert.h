// Conversions of the map transport (temporary-map tiles uplink, keyframe and delta tiles
// downlink) between LCM messages and core types, each checked: the tile's CRC, the window its
// frame covers, sizes. Resolutions travel as float and are snapped to the micrometre on
// arrival, so that 0.05 m stays exactly the static map's 0.05 m.
#pragma once

#include "core/codec/temp_map_tiles.h"
#include "core/map/map_replica.h"
#include "fleetmap/map_delta_t.hpp"
#include "fleetmap/map_keyframe_t.hpp"
#include "fleetmap/tempmap_tile_t.hpp"

namespace fleetmap::lcmtypes {

fleetmap::tempmap_tile_t ToMessage(const core::TempMapTile& tile, int64_t utime);
core::Result<core::TempMapTile> FromMessage(const fleetmap::tempmap_tile_t& msg);

fleetmap::map_keyframe_t ToMessage(const core::KeyframeTile& tile, int64_t utime);
core::Result<core::KeyframeTile> FromMessage(const fleetmap::map_keyframe_t& msg);

fleetmap::map_delta_t ToMessage(const core::DeltaTile& tile, int64_t utime);
core::Result<core::DeltaTile> FromMessage(const fleetmap::map_delta_t& msg);

// A float resolution from the wire as the double it was meant to be (micrometre grid).
double SnapResolution(float resolution_m);

}  // namespace fleetmap::lcmtypes
