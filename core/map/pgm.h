// 8-bit greyscale images in the netpbm PGM format, binary (P5) and plain ASCII (P2): the
// image format of ROS map_server maps. Files are outside data: every malformed header,
// truncated raster or absurd size is a Status, and the size is checked before allocating.
//
// Accepted: '#' comments wherever the header allows whitespace (also between P2 values), any
// whitespace, maxval 1..255 (pixels are rescaled to 0..255, rounded, when maxval < 255).
// Refused: other magic numbers (P1/P4 bitmaps, P3/P6 colour), maxval > 255 (16-bit PGM,
// Unimplemented), zero sizes, more than kMaxGridCells pixels, pixel values above maxval.
// Trailing data after the last pixel: see PgmReadOptions.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"

namespace fleetmap::core {

// A greyscale picture as stored in image files: row 0 is the TOP row (not the grid's bottom).
struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // row-major, width * height values, 0 black .. 255 white

  uint8_t at(int x, int row) const { return pixels[static_cast<size_t>(row) * width + x]; }
  void set(int x, int row, uint8_t v) { pixels[static_cast<size_t>(row) * width + x] = v; }
};

enum class PgmFormat { kBinary /* P5 */, kAscii /* P2 */ };

struct PgmReadOptions {
  // What follows the last pixel. true: ignored (netpbm allows several images in one file,
  // and SDL_image, which ROS map_server reads PGMs with, ignores it). false: refused as
  // DataLoss, except whitespace and comments after the last value of a P2 file.
  bool allow_trailing_data = true;
};

// Files larger than this are refused before reading (a P2 file of kMaxGridCells pixels at
// "255 " per pixel plus generous room for comments).
constexpr int64_t kMaxPgmFileBytes = int64_t{1} << 30;

Result<GrayImage> DecodePgm(std::string_view bytes, const PgmReadOptions& options = {});

// The image must be consistent (pixels.size() == width * height, sizes positive). Writes
// maxval 255 and no comments; P2 lines stay under 70 characters as netpbm recommends.
std::string EncodePgm(const GrayImage& image, PgmFormat format = PgmFormat::kBinary);

// Reads and decodes a file. Errors name the path.
Result<GrayImage> ReadPgmFile(const std::string& path, const PgmReadOptions& options = {});

// Encodes and writes a file atomically (see WriteFileAtomically).
Status WritePgmFile(const GrayImage& image, const std::string& path,
                    PgmFormat format = PgmFormat::kBinary);

}  // namespace fleetmap::core
