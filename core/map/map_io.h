// Maps in the ROS map_server format: a YAML file plus an image (PGM, PNG, ...), the format
// every 2D SLAM system exports. Loading follows map_server's semantics:
//
//   YAML keys (all required except mode; other keys are ignored):
//     image: path of the image, relative to the YAML file's folder, or absolute
//     resolution: metres per pixel, > 0
//     origin: [x, y, yaw], pose of the lower-left pixel's outer corner (yaw honoured)
//     negate: 0 or 1 (also false/true): swaps the meaning of black and white
//     occupied_thresh, free_thresh: 0 < free_thresh < occupied_thresh < 1
//     mode: trinary (default), scale or raw
//   A pixel's shade v is the mean of its colour channels (0..255; in trinary mode an alpha
//   channel is averaged in, as map_server does); with negate, v becomes 255 - v.
//     trinary: p = (255 - v) / 255; p > occupied_thresh: occupied, p < free_thresh: free,
//              otherwise unknown (cells get the grid's canonical log-odds).
//     scale:   occupied and free as in trinary; in between, the cell stores p itself as
//              log-odds (clamped by the grid), and a pixel that is not fully opaque is unknown.
//              map_server instead rescales p between the thresholds to 0..100; storing p keeps
//              such cells unknown under the file's thresholds.
//     raw:     v (after negate, as in ROS 1 map_server) is the occupancy percentage: 0..100
//              store p = v / 100 as log-odds (clamped), any other value (101..255) is unknown.
//              ROS 1 passes 101..255 on as invalid negative values (255 = -1, unknown),
//              nav2 maps them to unknown; both treat them as unknown.
//   Image row 0 is the top of the map (largest y); grid row 0 is the bottom, so rows flip.
//
// Saving writes <yaml stem>.pgm beside the YAML, like map_saver. Every error is a Status
// naming the file and, for YAML errors, the key; yaml-cpp and OpenCV exceptions never escape.
#pragma once

#include <string>

#include "core/map/log_odds.h"
#include "core/map/map_yaml.h"
#include "core/map/occupancy_grid.h"
#include "core/map/pgm.h"
#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::core {

struct MapLoadOptions {
  LogOddsLimits limits;  // clamping bounds of the loaded grid; occupied/free become max/min
  PgmReadOptions pgm;    // how strictly PGM images are read
};

struct LoadedMap {
  OccupancyGrid grid;
  MapMetadata metadata;
};

// Loads the YAML and its image. Images ending in .pgm (any case) are read by core/pgm, all
// others by OpenCV (8-bit, 1, 3 or 4 channels). Images over kMaxGridCells pixels are
// refused; for PGM and PNG before the pixels are decoded.
Result<LoadedMap> LoadMapServerMap(const std::string& yaml_path,
                                   const MapLoadOptions& options = {});

struct MapSaveOptions {
  // trinary: occupied 0, free 254, unknown 205, and the YAML says occupied_thresh 0.65,
  //   free_thresh 0.196 whatever `thresholds` are (the values that decode 0/254/205), as
  //   map_saver does.
  // scale: the grey is 255 * (1 - p), moved a step where rounding crosses a threshold, so
  //   each cell loads with its tri-state under `thresholds`; the YAML carries them. Cells
  //   between the thresholds load with p within 1/255; occupied and free cells load with
  //   the grid's canonical log-odds (as map_server reports them 100 and 0).
  // raw: the grey is the percentage round(100 p), and 255 for never observed cells
  //   (log-odds exactly 0).
  MapMode mode = MapMode::kTrinary;
  // Classify cells in trinary and scale mode. Scale mode needs free_probability and
  // occupied_probability at least 2/255 apart, so that a grey exists between them.
  OccupancyThresholds thresholds;
  PgmFormat pgm_format = PgmFormat::kBinary;  // P5, or P2 for diffable text files
  Status Validate() const;
};

// Writes <folder>/<stem>.pgm, then `yaml_path`, each atomically (WriteFileAtomically), the
// image first so that a YAML never names a missing image. If the YAML write fails after the
// image was written, the new image stays beside the old (or absent) YAML.
Status SaveMapServerMap(const OccupancyGrid& grid, const std::string& yaml_path,
                        const MapSaveOptions& options = {});

}  // namespace fleetmap::core
