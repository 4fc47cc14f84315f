// An image file decoded to 8-bit pixels, for map images that are not PGM (PNG, ...).
//
// Decoding lives in fleetmap_core_image (core/image/, OpenCV's image codecs), not in
// fleetmap_core: those codecs pull in ~140 shared libraries and ~45 MB of resident memory,
// too much for a vehicle computer. core/map/map_io.cc calls DecodeImageFile only where a program
// links fleetmap_core_image; other programs (the vehicle agent) read PGM maps only and say
// so when given another format.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::core {

struct DecodedImage {
  int width = 0;
  int height = 0;
  int channels = 0;             // 1 (grey), 3 (B, G, R) or 4 (B, G, R, alpha)
  std::vector<uint8_t> pixels;  // row 0 at the top, channels interleaved, 8 bits each
};

// Decodes any 8-bit image OpenCV reads, with 1, 3 or 4 channels, at most kMaxGridCells
// pixels. Defined in core/image/map_render.cc.
Result<DecodedImage> DecodeImageFile(const std::string& path);

}  // namespace fleetmap::core
