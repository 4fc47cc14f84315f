#include "core/io/crc32.h"

#include <zlib.h>

#include <algorithm>
#include <limits>

namespace fleetmap::core {

uint32_t Crc32(const uint8_t* data, size_t size) {
  uLong crc = crc32(0L, Z_NULL, 0);
  // zlib takes uInt lengths: feed large buffers in pieces.
  while (size > 0) {
    const size_t n = std::min<size_t>(size, std::numeric_limits<uInt>::max());
    crc = crc32(crc, data, static_cast<uInt>(n));
    data += n;
    size -= n;
  }
  return static_cast<uint32_t>(crc);
}

}  // namespace fleetmap::core
