// A whole grid as the tiles of one keyframe of `version`, in tile order, as a replica
// receives them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/codec/tile_delta.h"
#include "core/map/map_replica.h"

namespace fleetmap::core::testing {

inline std::vector<KeyframeTile> Keyframe(const OccupancyGrid& g, int32_t version) {
  std::vector<KeyframeTile> out;
  const std::vector<EncodedTile> tiles = EncodeAllTiles(g);
  for (size_t i = 0; i < tiles.size(); ++i)
    out.push_back({version, g.geometry(), 64, static_cast<int32_t>(i),
                   static_cast<int32_t>(tiles.size()), tiles[i].index, tiles[i].frame});
  return out;
}

}  // namespace fleetmap::core::testing
