// LCM payloads as fuzz inputs. A single-message target hands its whole input to
// lcmtypes::Decode<T>, exactly as a process's handler does. A stateful target (the temporary-map
// assembler, the map replica) needs many messages per input: LCM encodings delimit themselves,
// so its input is simply messages one after the other, each starting with its type's
// fingerprint, and real message sequences are its seeds. Tile messages carry two checksums,
// repaired here as checksum_repair.h explains.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "core/codec/map_codec.h"
#include "core/result.h"
#include "fleetmap/map_tile_t.hpp"
#include "fuzz/checksum_repair.h"

namespace fleetmap::fuzz {

// True if the 8 bytes at `pos` are T's fingerprint (LCM writes it big-endian).
template <typename T>
bool StartsWithType(const uint8_t* data, size_t size, size_t pos) {
  if (size - pos < 8) return false;
  const auto hash = static_cast<uint64_t>(T::getHash());
  for (int i = 0; i < 8; ++i) {
    if (data[pos + i] != static_cast<uint8_t>(hash >> (56 - 8 * i))) return false;
  }
  return true;
}

// Decodes the message starting at `pos` and moves `pos` past it. Errors as lcmtypes::Decode,
// which also catches what a generated decoder may throw (std::bad_alloc).
template <typename T>
core::Result<T> DecodeAt(const uint8_t* data, size_t size, size_t& pos) {
  T msg;
  try {
    const int used = msg.decode(data, static_cast<int>(pos), static_cast<int>(size - pos));
    if (used < 0) return core::DataLoss("malformed LCM message");
    pos += static_cast<size_t>(used);
  } catch (const std::exception& e) {
    return core::DataLoss(e.what());
  }
  return msg;
}

// A map_tile_t: the codec frame's own CRC, then the message's payload size and CRC fields.
inline bool RepairTileMessage(fleetmap::map_tile_t& tile) {
  bool changed = false;
  if (tile.payload.size() >= core::kCodecHeaderBytes + core::kCodecTrailerBytes) {
    changed |= RepairTrailingCrc32(tile.payload);
  }
  const auto size = static_cast<int32_t>(tile.payload.size());
  const auto crc = static_cast<int32_t>(core::Crc32(tile.payload.data(), tile.payload.size()));
  changed |= tile.payload_size != size || tile.crc32 != crc;
  tile.payload_size = size;
  tile.crc32 = crc;
  return changed;
}

// The LCM encoding of `msg`, for seeds.
template <typename T>
std::string EncodeLcm(const T& msg) {
  std::string bytes(static_cast<size_t>(msg.getEncodedSize()), '\0');
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace fleetmap::fuzz
