#include "ops/lan/change_cost.h"

#include <cstdio>
#include <map>
#include <set>

#include "auth/trailer.h"
#include "fleetmap/map_delta_t.hpp"
#include "fleetmap/map_keyframe_t.hpp"
#include "lcmtypes/convert.h"

namespace fleetmap::ops::lan {
namespace {

// Per version: tile index -> payload bytes of its first copy, and the tile count.
struct VersionTiles {
  std::map<int32_t, int64_t> bytes_by_tile;
  int32_t tile_count = 0;
  int64_t Total() const {
    int64_t sum = 0;
    for (const auto& [index, bytes] : bytes_by_tile) sum += bytes;
    return sum;
  }
};

void Add(VersionTiles& v, int32_t index, int32_t count, size_t bytes) {
  v.tile_count = count;
  v.bytes_by_tile.emplace(index, static_cast<int64_t>(bytes));
}

std::string Num(double v) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}

}  // namespace

ChangeCost MeasureChangeCost(const std::vector<LogMessage>& messages) {
  std::map<int32_t, VersionTiles> deltas;
  // The rolling keyframe's tiles are of several versions: a whole keyframe is the latest copy
  // of every tile.
  std::map<int32_t, int64_t> keyframe_tile_bytes;
  int32_t keyframe_tile_count = 0;
  ChangeCost cost;
  for (const LogMessage& m : messages) {
    const int size = static_cast<int>(auth::PayloadSize(m.data.data(), m.data.size()));
    if (m.channel == lcmtypes::kMapDeltaChannel) {
      auto d = lcmtypes::Decode<fleetmap::map_delta_t>(m.data.data(), size);
      if (d.ok()) Add(deltas[d->new_version], d->tile_index, d->tile_count, m.data.size());
    } else if (m.channel == lcmtypes::kMapKeyframeChannel) {
      auto k = lcmtypes::Decode<fleetmap::map_keyframe_t>(m.data.data(), size);
      if (!k.ok()) continue;
      keyframe_tile_bytes[k->tile_index] = static_cast<int64_t>(m.data.size());
      keyframe_tile_count = k->tile_count;
      cost.map_cells = int64_t{k->width_cells} * k->height_cells;
    }
  }
  double delta_bytes = 0, delta_tiles = 0, keyframe_bytes = 0;
  for (const auto& [version, v] : deltas) {
    ++cost.changes;
    delta_bytes += v.Total();
    delta_tiles += v.tile_count;
  }
  if (keyframe_tile_count > 0 && int(keyframe_tile_bytes.size()) == keyframe_tile_count) {
    cost.keyframes_complete = 1;
    for (const auto& [index, bytes] : keyframe_tile_bytes) keyframe_bytes += bytes;
    cost.keyframe_tiles = keyframe_tile_count;
  }
  if (cost.changes > 0) {
    cost.delta_bytes_mean = delta_bytes / cost.changes;
    cost.delta_tiles_mean = delta_tiles / cost.changes;
  }
  if (cost.keyframes_complete > 0) cost.keyframe_bytes = keyframe_bytes / cost.keyframes_complete;
  if (cost.map_cells > 0) cost.occupancy_grid_bytes = cost.map_cells + kOccupancyGridHeaderBytes;
  return cost;
}

std::string ChangeCostFigureLines(const ChangeCost& c) {
  std::string out;
  out += "changes.count " + std::to_string(c.changes) + " count\n";
  out += "changes.delta_bytes_mean " + Num(c.delta_bytes_mean) + " B\n";
  out += "changes.delta_tiles_mean " + Num(c.delta_tiles_mean) + " tiles\n";
  out += "changes.keyframes_complete " + std::to_string(c.keyframes_complete) + " count\n";
  out += "changes.keyframe_bytes " + Num(c.keyframe_bytes) + " B\n";
  out += "changes.keyframe_tiles " + std::to_string(c.keyframe_tiles) + " tiles\n";
  out += "changes.map_cells " + std::to_string(c.map_cells) + " cells\n";
  out += "changes.occupancy_grid_bytes " + std::to_string(c.occupancy_grid_bytes) + " B\n";
  return out;
}

}  // namespace fleetmap::ops::lan
