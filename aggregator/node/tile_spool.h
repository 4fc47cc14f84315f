// The tiles of incomplete temporary maps that the aggregator has acknowledged (PENDING),
// kept on disk: a vehicle's outbox never resends a tile it saw acknowledged, so a restarted
// aggregator that had forgotten them could never complete the map. One file per tile,
// <folder>/<hex vehicle id>.<sequence>.<index>.tile, holding the tile's LCM message as it
// arrived (it carries its own CRC), written atomically and fsynced before the
// acknowledgement names it. A map's files go once it is merged, rejected or dropped.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "aggregator/node/map_key.h"
#include "core/result.h"

namespace fleetmap::aggregator::node {

struct SpooledTile {
  MapKey key;
  int32_t index = 0;
  std::vector<uint8_t> bytes;  // the tempmap_tile_t message
};

class TileSpool {
 public:
  // Disabled: keeps nothing, Save fails.
  TileSpool() = default;
  // Creates `folder` if needed (IoError naming it otherwise).
  static core::Result<TileSpool> Open(const std::string& folder);

  bool enabled() const { return !folder_.empty(); }
  // Writes one tile (IoError: it is not kept; do not acknowledge it).
  core::Status Save(const MapKey& key, int32_t index, const std::vector<uint8_t>& bytes);
  bool Has(const MapKey& key, int32_t index) const;
  // Deletes every kept tile of the map.
  void Remove(const MapKey& key);

  // Every tile an earlier run kept, by vehicle, sequence and index. Files whose names are not ours
  // are left alone; unreadable ones are renamed to *.bad and counted in `bad_files`.
  std::vector<SpooledTile> LoadAll(int* bad_files);

 private:
  explicit TileSpool(std::string folder) : folder_(std::move(folder)) {}
  std::string PathOf(const MapKey& key, int32_t index) const;

  std::string folder_;
  std::map<MapKey, std::set<int32_t>> saved_;
};

}  // namespace fleetmap::aggregator::node
