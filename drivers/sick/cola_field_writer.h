// Writers of CoLa telegram fields, the mirror of cola_field_reader.h: the emulator and the
// tests build telegrams with them. CoLa-A writes upper-case hex tokens separated by spaces
// (a signed value as its two's complement), CoLa-B big-endian binary.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace fleetmap::drivers::sick {

class BinaryFieldWriter {
 public:
  explicit BinaryFieldWriter(std::string& out) : out_(out) {}
  void U8(uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void U16(uint16_t v) {
    U8(static_cast<uint8_t>(v >> 8));
    U8(static_cast<uint8_t>(v));
  }
  void U32(uint32_t v) {
    U16(static_cast<uint16_t>(v >> 16));
    U16(static_cast<uint16_t>(v));
  }
  void I32(int32_t v) { U32(static_cast<uint32_t>(v)); }
  void F32(float v);
  void Fixed(std::string_view s) { out_.append(s); }
  void String8(std::string_view s) {
    U8(static_cast<uint8_t>(s.size()));
    out_.append(s);
  }
  void Value16(uint16_t v) { U16(v); }
  void Value8(uint16_t v) { U8(static_cast<uint8_t>(v)); }

 private:
  std::string& out_;
};

class AsciiFieldWriter {
 public:
  // `out` already holds the command ("sSN LMDscandata"); each field adds " <token>".
  explicit AsciiFieldWriter(std::string& out) : out_(out) {}
  void U8(uint8_t v) { Hex(v); }
  void U16(uint16_t v) { Hex(v); }
  void U32(uint32_t v) { Hex(v); }
  void I32(int32_t v) { Hex(static_cast<uint32_t>(v)); }
  void F32(float v);
  void Fixed(std::string_view s) {
    out_.push_back(' ');
    out_.append(s);
  }
  void String8(std::string_view s) {
    Hex(static_cast<uint32_t>(s.size()));
    Fixed(s);
  }
  void Value16(uint16_t v) { Hex(v); }
  void Value8(uint16_t v) { Hex(v); }

 private:
  void Hex(uint32_t v);
  std::string& out_;
};

}  // namespace fleetmap::drivers::sick
