// The YAML half of a ROS map_server map (map_io.h describes the whole format): the keys as
// found in a file, read and checked, and written back as map_saver writes them. Apart from
// the pixels because the two change for different reasons: this half follows map_server's
// YAML keys, the other its image semantics.
#pragma once

#include <string>

#include "core/map/grid_geometry.h"
#include "core/map/log_odds.h"
#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::core {

enum class MapMode { kTrinary, kScale, kRaw };
const char* MapModeName(MapMode mode);  // "trinary", "scale", "raw": the YAML spelling

// The YAML half of a map_server map, as found in the file.
struct MapMetadata {
  std::string image_path;      // resolved: the YAML folder joined with a relative `image`
  double resolution_m = 0.05;  // metres per pixel
  Pose2 origin;                // x_m, y_m, theta_rad: the grid origin (GridGeometry)
  bool negate = false;
  OccupancyThresholds thresholds;  // occupied_thresh, free_thresh of the file
  MapMode mode = MapMode::kTrinary;
};

// Parses and validates YAML text; `yaml_path` resolves `image` and prefixes every error.
// Does not look at the image.
Result<MapMetadata> ParseMapYaml(const std::string& yaml_text, const std::string& yaml_path);

// The thresholds written with a trinary image: they decode 0, 254 and 205, as map_saver's.
constexpr double kTrinaryOccupiedThreshold = 0.65;
constexpr double kTrinaryFreeThreshold = 0.196;

// The YAML text of a map whose image is `image_name` (beside the YAML): numbers written so
// that they read back exactly, whatever the locale; in trinary mode the thresholds are the
// two above, otherwise `thresholds`. Fails on an image name YAML cannot hold.
Result<std::string> MapYamlText(const GridGeometry& g, const std::string& image_name, MapMode mode,
                                const OccupancyThresholds& thresholds);

}  // namespace fleetmap::core
