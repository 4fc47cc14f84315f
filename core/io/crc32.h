// CRC-32 (IEEE 802.3, the zlib/PNG polynomial) over a byte range. Computed by zlib.
#pragma once

#include <cstddef>
#include <cstdint>

namespace fleetmap::core {

uint32_t Crc32(const uint8_t* data, size_t size);

}  // namespace fleetmap::core
