// Pictures of occupancy grids: free white, occupied black, unknown grey, with the grid's
// bottom row (row 0, at the origin) at the bottom of the picture, as a map is drawn.
//
// OpenCV stays out of this header: BgrImage stores its bytes in OpenCV's CV_8UC3 order, so
// code that draws coloured layers on top wraps it without a copy:
//   cv::Mat mat(image.height, image.width, CV_8UC3, image.pixels.data());
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/map/log_odds.h"
#include "core/map/occupancy_grid.h"
#include "core/result.h"

namespace fleetmap::core {

struct Bgr {
  uint8_t b = 0;
  uint8_t g = 0;
  uint8_t r = 0;
  bool operator==(const Bgr& o) const { return b == o.b && g == o.g && r == o.r; }
  bool operator!=(const Bgr& o) const { return !(*this == o); }
};

// A colour picture: row 0 is the TOP row, 3 bytes per pixel in B, G, R order.
struct BgrImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // width * height * 3 bytes, row-major

  Bgr at(int x, int row) const {
    const size_t i = (static_cast<size_t>(row) * width + x) * 3;
    return {pixels[i], pixels[i + 1], pixels[i + 2]};
  }
  void set(int x, int row, Bgr c) {
    const size_t i = (static_cast<size_t>(row) * width + x) * 3;
    pixels[i] = c.b;
    pixels[i + 1] = c.g;
    pixels[i + 2] = c.r;
  }
};

struct RenderOptions {
  // Each cell becomes a square of scale_pixels_per_cell x scale_pixels_per_cell pixels, to
  // enlarge small maps. 1..64, and the picture stays within kMaxGridCells pixels.
  int scale_pixels_per_cell = 1;
  OccupancyThresholds thresholds;    // classify cells into the three colours
  Bgr free_color{255, 255, 255};     // white
  Bgr occupied_color{0, 0, 0};       // black
  Bgr unknown_color{205, 205, 205};  // map_saver's unknown grey
  Status Validate() const;
};

// The picture of a grid (InvalidArgument / OutOfRange for bad options).
Result<BgrImage> RenderGrid(const OccupancyGrid& grid, const RenderOptions& options = {});

// Encodes as PNG and writes it atomically (core/map/pgm.h WriteFileAtomically).
Status WritePng(const BgrImage& image, const std::string& path);

// RenderGrid then WritePng.
Status RenderGridToPng(const OccupancyGrid& grid, const std::string& path,
                       const RenderOptions& options = {});

// Reads any image OpenCV decodes (PNG, PGM, ...) as 8-bit colour, e.g. to check or overlay a
// rendered picture. Images over kMaxGridCells pixels are refused after decoding, so this is
// for our own pictures; maps from outside go through LoadMapServerMap (core/map/map_io.h).
Result<BgrImage> ReadBgrImage(const std::string& path);

}  // namespace fleetmap::core
