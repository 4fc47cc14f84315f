// Checksum repair for fuzz targets. A mutated byte breaks a CRC-32 with probability
// 1 - 2^-32, so without repair libFuzzer would spend nearly every execution on the
// "checksum mismatch" branch and never reach the parsers behind it. Each target therefore
// runs an input as it is (the checksum checks stay covered) and, when the checksum was wrong,
// once more with it repaired. The repair mirrors what each encoder writes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/io/crc32.h"
#include "drivers/sick/cola_frame.h"
#include "drivers/sick/s300_telegram.h"

namespace fleetmap::fuzz {

inline void PutLe32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}

// The trailing little-endian CRC-32 of everything before it (codec frames, temp-map files).
// Returns true if a byte changed.
inline bool RepairTrailingCrc32(std::vector<uint8_t>& bytes) {
  if (bytes.size() < 4) return false;
  uint8_t want[4];
  PutLe32(want, core::Crc32(bytes.data(), bytes.size() - 4));
  bool changed = false;
  for (int i = 0; i < 4; ++i) {
    changed |= bytes[bytes.size() - 4 + i] != want[i];
    bytes[bytes.size() - 4 + i] = want[i];
  }
  return changed;
}

// CoLa-B frames in a byte stream: every "02 02 02 02 <u32 length>" whose payload fits in the
// stream gets the XOR byte it needs.
inline bool RepairColaBChecksums(std::string& stream) {
  bool changed = false;
  auto* p = reinterpret_cast<uint8_t*>(stream.data());
  const size_t n = stream.size();
  for (size_t i = 0; i + drivers::sick::kColaBHeaderBytes <= n; ++i) {
    if (p[i] != 2 || p[i + 1] != 2 || p[i + 2] != 2 || p[i + 3] != 2) continue;
    const size_t length = (size_t{p[i + 4]} << 24) | (size_t{p[i + 5]} << 16) |
                          (size_t{p[i + 6]} << 8) | size_t{p[i + 7]};
    const size_t body = i + drivers::sick::kColaBHeaderBytes;
    if (length > n - body || n - body - length < 1) continue;
    const uint8_t want = drivers::sick::ColaBChecksum(p + body, length);
    changed |= p[body + length] != want;
    p[body + length] = want;
    i = body + length;
  }
  return changed;
}

// An S300 telegram: CRC-16 over bytes 4 up to the trailing little-endian CRC.
inline bool RepairS300Crc(std::vector<uint8_t>& telegram) {
  if (telegram.size() < 6) return false;
  const uint16_t want = drivers::sick::Crc16Ccitt(telegram.data() + 4, telegram.size() - 6);
  const uint8_t lo = static_cast<uint8_t>(want), hi = static_cast<uint8_t>(want >> 8);
  const bool changed = telegram[telegram.size() - 2] != lo || telegram[telegram.size() - 1] != hi;
  telegram[telegram.size() - 2] = lo;
  telegram[telegram.size() - 1] = hi;
  return changed;
}

}  // namespace fleetmap::fuzz
