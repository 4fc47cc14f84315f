// The map codec: a framed, versioned, CRC32-checked, compressed encoding of a rectangular
// window of an occupancy grid. A frame says which cells it holds and how; where the grid lies
// in the world travels beside it (in the LCM message). Frame layout, little-endian:
//
//   offset size field
//   0      4    magic "FMCF"
//   4      1    format version (kCodecFormatVersion)
//   5      1    cell packing (CellPacking)
//   6      1    compression (Compression)
//   7      1    reserved, 0
//   8      4    x0 of the window, cells (int32)
//   12     4    y0 of the window, cells (int32)
//   16     4    width, cells (uint32)
//   20     4    height, cells (uint32)
//   24     4    packed size: bytes of packed cells before compression (uint32)
//   28     4    payload size: bytes that follow (uint32)
//   32     n    payload: the packed cells, compressed
//   32+n   4    CRC-32 of bytes [0, 32+n)
//
// Decoding checks everything before it allocates or writes: a corrupt, truncated, oversized
// or hostile frame (a decompression bomb) is a Status, never a crash or a half-written grid.
#pragma once

#include <cstdint>
#include <vector>

#include "core/codec/cell_packing.h"

namespace fleetmap::core {

constexpr uint8_t kCodecFormatVersion = 1;
constexpr size_t kCodecHeaderBytes = 32;
constexpr size_t kCodecTrailerBytes = 4;

enum class Compression : uint8_t { kNone = 0, kZstd = 1, kZlib = 2 };
const char* CompressionName(Compression compression);

struct CodecOptions {
  CellPacking packing = CellPacking::kTriState2Bit;
  Compression compression = Compression::kZstd;
  int level = 3;  // zstd 1..19 or zlib 1..9; 3 measured as the speed/size knee for tiles
  OccupancyThresholds thresholds;  // for the tri-state packings
};

// Limits a decoder imposes on frames from outside, so that a frame cannot make it allocate
// more than the caller expects.
struct DecodeLimits {
  int64_t max_cells = kMaxGridCells;   // width * height of one frame
  size_t max_frame_bytes = 64u << 20;  // whole frame, header and trailer included
};

// Encodes `window` (inside the grid) of `grid`.
std::vector<uint8_t> EncodeWindow(const OccupancyGrid& grid, const CellWindow& window,
                                  const CodecOptions& options = {});

struct DecodedFrame {
  CellWindow window;
  CellPacking packing = CellPacking::kTriState2Bit;
  Compression compression = Compression::kNone;
  PackedValues values;  // window.num_cells() values, row by row, bottom row first
};

Result<DecodedFrame> DecodeFrame(const uint8_t* data, size_t size, const DecodeLimits& limits = {});
inline Result<DecodedFrame> DecodeFrame(const std::vector<uint8_t>& frame,
                                        const DecodeLimits& limits = {}) {
  return DecodeFrame(frame.data(), frame.size(), limits);
}

// Writes a decoded frame into `grid`; refuses (and leaves the grid untouched) when the
// frame's window does not lie inside the grid.
Status ApplyFrame(const DecodedFrame& frame, OccupancyGrid& grid);

}  // namespace fleetmap::core
