// What one change of the current map cost on the downlink, three ways: the tile delta the
// aggregator sent (MAP_DELTA, each tile once), a whole keyframe (MAP_KEYFRAME, the latest copy
// of every tile: the rolling keyframe's tiles are of several versions) and a ROS
// nav_msgs/OccupancyGrid of the whole map (1 byte per cell plus its header), the way a ROS map
// server republishes the map on every change.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ops/lan/lan_log.h"

namespace fleetmap::ops::lan {

// Serialized nav_msgs/OccupancyGrid without its cells: std_msgs/Header (seq 4, stamp 8,
// frame_id "map" 4 + 3), MapMetaData (map_load_time 8, resolution 4, width 4, height 4,
// origin 7 x 8) and the cell array's length (4).
constexpr int64_t kOccupancyGridHeaderBytes = 103;

struct ChangeCost {
  int changes = 0;                   // versions the aggregator sent a MAP_DELTA for
  double delta_bytes_mean = 0.0;     // LCM payload bytes of one change's tiles, each once
  double delta_tiles_mean = 0.0;     // tiles of one change
  int keyframes_complete = 0;        // 1 when every tile of the map was logged, else 0
  double keyframe_bytes = 0.0;       // one whole keyframe's payload bytes
  int keyframe_tiles = 0;            // tiles of the whole map
  int64_t map_cells = 0;             // width x height of the current map (from keyframes)
  int64_t occupancy_grid_bytes = 0;  // map_cells + kOccupancyGridHeaderBytes; 0: no keyframe
};

// From a downlink log's messages.
ChangeCost MeasureChangeCost(const std::vector<LogMessage>& messages);

// `changes.<figure> value unit` lines.
std::string ChangeCostFigureLines(const ChangeCost& cost);

}  // namespace fleetmap::ops::lan
