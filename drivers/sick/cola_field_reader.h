// Readers of the typed fields of a CoLa telegram's arguments, one per protocol, with the same
// interface so that one template parses both (scan_telegram_parser.cc):
//   CoLa-B: big-endian binary; a float is 4 IEEE-754 bytes.
//   CoLa-A: space-separated ASCII tokens; unsigned and signed numbers in hex (a signed 32-bit
//   value is its two's complement, "FFF92230" = -450000), or decimal with a leading '+'/'-';
//   a float is the hex of its IEEE-754 bits ("3F800000" = 1.0).
// Both readers never read past the end: a short or malformed field sets a sticky failure
// flag and returns zero; the caller turns failed() into a DataLoss status.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace fleetmap::drivers::sick {

class BinaryFieldReader {
 public:
  explicit BinaryFieldReader(std::string_view bytes)
      : p_(reinterpret_cast<const uint8_t*>(bytes.data())), size_(bytes.size()) {}

  uint8_t U8() { return Has(1) ? p_[pos_++] : Fail(); }
  uint16_t U16() {
    if (!Has(2)) return Fail();
    const uint16_t v = static_cast<uint16_t>((p_[pos_] << 8) | p_[pos_ + 1]);
    pos_ += 2;
    return v;
  }
  uint32_t U32() {
    if (!Has(4)) return Fail();
    const uint32_t v = (uint32_t{p_[pos_]} << 24) | (uint32_t{p_[pos_ + 1]} << 16) |
                       (uint32_t{p_[pos_ + 2]} << 8) | uint32_t{p_[pos_ + 3]};
    pos_ += 4;
    return v;
  }
  int32_t I32() { return static_cast<int32_t>(U32()); }
  float F32() {
    const uint32_t bits = U32();
    float v;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  }
  // A fixed-length string ("DIST1": 5 bytes).
  std::string Fixed(size_t n) {
    if (!Has(n)) return Fail(), std::string();
    std::string s(reinterpret_cast<const char*>(p_ + pos_), n);
    pos_ += n;
    return s;
  }
  // A string preceded by its length as one byte.
  std::string String8() { return Fixed(U8()); }
  // Reads n 16-bit (or 8-bit) values into out[0..n), or fails without writing if short.
  bool Values16(uint16_t* out, size_t n) {
    if (n > remaining() / 2) return Fail(), false;
    for (size_t i = 0; i < n; ++i, pos_ += 2)
      out[i] = static_cast<uint16_t>((p_[pos_] << 8) | p_[pos_ + 1]);
    return true;
  }
  bool Values8(uint16_t* out, size_t n) {
    if (n > remaining()) return Fail(), false;
    for (size_t i = 0; i < n; ++i) out[i] = p_[pos_++];
    return true;
  }
  // An upper bound of the values still readable (to check counts before allocating).
  size_t MaxValuesLeft() const { return remaining(); }

  bool failed() const { return failed_; }
  size_t remaining() const { return size_ - pos_; }

 private:
  bool Has(size_t n) const { return !failed_ && n <= size_ - pos_; }
  uint8_t Fail() {
    failed_ = true;
    return 0;
  }

  const uint8_t* p_;
  size_t size_;
  size_t pos_ = 0;
  bool failed_ = false;
};

class AsciiFieldReader {
 public:
  explicit AsciiFieldReader(std::string_view text) : s_(text) {}

  uint8_t U8() { return static_cast<uint8_t>(Unsigned(0xFF)); }
  uint16_t U16() { return static_cast<uint16_t>(Unsigned(0xFFFF)); }
  uint32_t U32() { return static_cast<uint32_t>(Unsigned(0xFFFFFFFFu)); }
  int32_t I32();
  float F32() {
    const uint32_t bits = U32();
    float v;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  }
  std::string Fixed(size_t n) {
    const std::string_view t = Token();
    if (t.size() != n) return Fail(), std::string();
    return std::string(t);
  }
  // Length token (hex), one space, then that many characters (which may contain spaces).
  std::string String8();
  bool Values16(uint16_t* out, size_t n) { return Values(out, n, 0xFFFF); }
  bool Values8(uint16_t* out, size_t n) { return Values(out, n, 0xFF); }
  // Every value takes at least two characters ("0 ").
  size_t MaxValuesLeft() const { return (remaining() + 1) / 2; }

  bool failed() const { return failed_; }
  size_t remaining() const { return s_.size() - pos_; }

 private:
  std::string_view Token();
  uint64_t Unsigned(uint64_t max);
  bool Values(uint16_t* out, size_t n, uint32_t max);
  uint64_t Fail() {
    failed_ = true;
    return 0;
  }

  std::string_view s_;
  size_t pos_ = 0;
  bool failed_ = false;
};

}  // namespace fleetmap::drivers::sick
