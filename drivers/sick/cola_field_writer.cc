#include "drivers/sick/cola_field_writer.h"

#include <cstring>

namespace fleetmap::drivers::sick {

void BinaryFieldWriter::F32(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof(bits));
  U32(bits);
}

void AsciiFieldWriter::F32(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof(bits));
  Hex(bits);
}

void AsciiFieldWriter::Hex(uint32_t v) {
  static const char kDigits[] = "0123456789ABCDEF";
  char buf[9];
  int n = 0;
  do {
    buf[n++] = kDigits[v & 0xF];
    v >>= 4;
  } while (v != 0);
  out_.push_back(' ');
  while (n > 0) out_.push_back(buf[--n]);
}

}  // namespace fleetmap::drivers::sick
