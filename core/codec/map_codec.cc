#include "core/codec/map_codec.h"

#include <zlib.h>
#include <zstd.h>

#include <memory>
#include <string>

#include "core/io/byte_io.h"
#include "core/io/crc32.h"

namespace fleetmap::core {
namespace {

constexpr uint8_t kMagic[4] = {'F', 'M', 'C', 'F'};

// zstd contexts cost more to create than a 64 x 64 tile costs to compress, so each thread
// keeps one of each for its lifetime.
ZSTD_CCtx* CompressionContext() {
  thread_local std::unique_ptr<ZSTD_CCtx, size_t (*)(ZSTD_CCtx*)> ctx(ZSTD_createCCtx(),
                                                                      ZSTD_freeCCtx);
  return ctx.get();
}
ZSTD_DCtx* DecompressionContext() {
  thread_local std::unique_ptr<ZSTD_DCtx, size_t (*)(ZSTD_DCtx*)> ctx(ZSTD_createDCtx(),
                                                                      ZSTD_freeDCtx);
  return ctx.get();
}

std::vector<uint8_t> Compress(const std::vector<uint8_t>& raw, Compression c, int level) {
  std::vector<uint8_t> out;
  switch (c) {
    case Compression::kNone:
      return raw;
    case Compression::kZstd: {
      out.resize(ZSTD_compressBound(raw.size()));
      const size_t n = ZSTD_compressCCtx(CompressionContext(), out.data(), out.size(), raw.data(),
                                         raw.size(), level);
      assert(!ZSTD_isError(n) && "zstd cannot fail with a bound-sized output");
      out.resize(n);
      return out;
    }
    case Compression::kZlib: {
      uLongf n = compressBound(static_cast<uLong>(raw.size()));
      out.resize(n);
      const int rc = compress2(out.data(), &n, raw.data(), static_cast<uLong>(raw.size()), level);
      assert(rc == Z_OK && "zlib cannot fail with a bound-sized output");
      (void)rc;
      out.resize(n);
      return out;
    }
  }
  return out;
}

// Decompresses into exactly `expected` bytes. The output buffer is never larger than the
// size the header promised (and the header was checked against the cell limit), which is
// what defuses decompression bombs.
Result<std::vector<uint8_t>> Decompress(const uint8_t* in, size_t size, Compression c,
                                        size_t expected) {
  std::vector<uint8_t> out(expected);
  switch (c) {
    case Compression::kNone:
      if (size != expected) return DataLoss("uncompressed payload has the wrong size");
      out.assign(in, in + size);
      return out;
    case Compression::kZstd: {
      const unsigned long long declared = ZSTD_getFrameContentSize(in, size);
      if (declared == ZSTD_CONTENTSIZE_ERROR) return DataLoss("payload is not a zstd frame");
      if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != expected) {
        return DataLoss("zstd frame declares " + std::to_string(declared) + " bytes, header " +
                        std::to_string(expected));
      }
      const size_t n =
          ZSTD_decompressDCtx(DecompressionContext(), out.data(), out.size(), in, size);
      if (ZSTD_isError(n)) return DataLoss(std::string("zstd: ") + ZSTD_getErrorName(n));
      if (n != expected) return DataLoss("zstd payload decompressed to the wrong size");
      return out;
    }
    case Compression::kZlib: {
      uLongf n = static_cast<uLongf>(expected);
      const int rc = uncompress(out.data(), &n, in, static_cast<uLong>(size));
      if (rc != Z_OK) return DataLoss("zlib payload is corrupt or larger than declared");
      if (n != expected) return DataLoss("zlib payload decompressed to the wrong size");
      return out;
    }
  }
  return DataLoss("unknown compression");
}

struct FrameHeader {
  uint8_t version, packing, compression;
  CellWindow window;
  uint32_t packed_size, payload_size;
};

Status CheckHeader(const FrameHeader& h, size_t payload_available, const DecodeLimits& limits) {
  if (h.version != kCodecFormatVersion) {
    return Unimplemented("codec format version " + std::to_string(h.version) +
                         " is not supported (this build reads version " +
                         std::to_string(kCodecFormatVersion) + ")");
  }
  if (!IsValidCellPacking(h.packing)) {
    return DataLoss("unknown cell packing " + std::to_string(h.packing));
  }
  if (h.compression > uint8_t(Compression::kZlib)) {
    return DataLoss("unknown compression " + std::to_string(h.compression));
  }
  if (h.window.width <= 0 || h.window.height <= 0 || h.window.x0 < 0 || h.window.y0 < 0) {
    return DataLoss("frame window is empty or negative");
  }
  if (h.window.num_cells() > limits.max_cells) {
    return OutOfRange("frame of " + std::to_string(h.window.num_cells()) +
                      " cells exceeds the limit of " + std::to_string(limits.max_cells));
  }
  const auto packing = static_cast<CellPacking>(h.packing);
  if (int64_t{h.packed_size} != PackedSize(packing, h.window.num_cells())) {
    return DataLoss("packed size " + std::to_string(h.packed_size) + " does not match a " +
                    std::to_string(h.window.width) + " x " + std::to_string(h.window.height) +
                    " window");
  }
  if (h.payload_size != payload_available) {
    return DataLoss("payload size field says " + std::to_string(h.payload_size) +
                    " bytes, the frame holds " + std::to_string(payload_available));
  }
  return OkStatus();
}

}  // namespace

const char* CompressionName(Compression compression) {
  switch (compression) {
    case Compression::kNone:
      return "none";
    case Compression::kZstd:
      return "zstd";
    case Compression::kZlib:
      return "zlib";
  }
  return "invalid";
}

std::vector<uint8_t> EncodeWindow(const OccupancyGrid& grid, const CellWindow& window,
                                  const CodecOptions& options) {
  const std::vector<uint8_t> packed = PackCells(grid, window, options.packing, options.thresholds);
  const std::vector<uint8_t> payload = Compress(packed, options.compression, options.level);
  std::vector<uint8_t> frame;
  frame.reserve(kCodecHeaderBytes + payload.size() + kCodecTrailerBytes);
  ByteWriter w(frame);
  w.Bytes(kMagic, 4);
  w.U8(kCodecFormatVersion);
  w.U8(uint8_t(options.packing));
  w.U8(uint8_t(options.compression));
  w.U8(0);
  w.I32(window.x0);
  w.I32(window.y0);
  w.U32(static_cast<uint32_t>(window.width));
  w.U32(static_cast<uint32_t>(window.height));
  w.U32(static_cast<uint32_t>(packed.size()));
  w.U32(static_cast<uint32_t>(payload.size()));
  w.Bytes(payload.data(), payload.size());
  w.U32(Crc32(frame.data(), frame.size()));
  return frame;
}

Result<DecodedFrame> DecodeFrame(const uint8_t* data, size_t size, const DecodeLimits& limits) {
  if (size > limits.max_frame_bytes) {
    return OutOfRange("frame of " + std::to_string(size) + " bytes exceeds the limit of " +
                      std::to_string(limits.max_frame_bytes));
  }
  if (size < kCodecHeaderBytes + kCodecTrailerBytes) {
    return DataLoss("frame of " + std::to_string(size) + " bytes is shorter than its header");
  }
  ByteReader r(data, size);
  const uint8_t* magic = r.Bytes(4);
  if (std::memcmp(magic, kMagic, 4) != 0) return DataLoss("not a codec frame (bad magic)");
  const uint32_t stored_crc = ByteReader(data + size - 4, 4).U32();
  if (Crc32(data, size - 4) != stored_crc) return DataLoss("codec frame CRC mismatch");
  FrameHeader h;
  h.version = r.U8();
  h.packing = r.U8();
  h.compression = r.U8();
  r.U8();  // reserved
  h.window.x0 = r.I32();
  h.window.y0 = r.I32();
  const uint32_t width = r.U32(), height = r.U32();
  // Sizes beyond int range are absurd; reject them before they overflow the window type.
  if (width > uint32_t{1} << 30 || height > uint32_t{1} << 30) {
    return OutOfRange("frame window " + std::to_string(width) + " x " + std::to_string(height) +
                      " is absurd");
  }
  h.window.width = static_cast<int>(width);
  h.window.height = static_cast<int>(height);
  h.packed_size = r.U32();
  h.payload_size = r.U32();
  FLEETMAP_RETURN_IF_ERROR(CheckHeader(h, size - kCodecHeaderBytes - kCodecTrailerBytes, limits));
  const auto compression = static_cast<Compression>(h.compression);
  auto packed = Decompress(r.Bytes(h.payload_size), h.payload_size, compression, h.packed_size);
  if (!packed.ok()) return packed.status();
  const auto packing = static_cast<CellPacking>(h.packing);
  auto values = UnpackCells(packed->data(), static_cast<int64_t>(packed->size()), packing,
                            h.window.num_cells());
  if (!values.ok()) return values.status();
  return DecodedFrame{h.window, packing, compression, std::move(values).value()};
}

Status ApplyFrame(const DecodedFrame& frame, OccupancyGrid& grid) {
  if (!grid.geometry().Contains(frame.window)) {
    return FailedPrecondition("frame window [" + std::to_string(frame.window.x0) + ", " +
                              std::to_string(frame.window.y0) + "] " +
                              std::to_string(frame.window.width) + " x " +
                              std::to_string(frame.window.height) + " lies outside the " +
                              grid.geometry().ToString() + " grid");
  }
  WriteCells(frame.values, frame.packing, frame.window, grid);
  return OkStatus();
}

}  // namespace fleetmap::core
