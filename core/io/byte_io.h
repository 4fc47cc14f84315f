// Little-endian writing and bounds-checked reading of fixed-size fields, for our own
// binary formats (codec frames, journals). A reader never reads past its end: a short read
// sets a sticky failure flag that the caller turns into a DataLoss status.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace fleetmap::core {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<uint8_t>& out) : out_(out) {}
  void U8(uint8_t v) { out_.push_back(v); }
  void U32(uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void I32(int32_t v) { U32(static_cast<uint32_t>(v)); }
  void U64(uint64_t v) {
    for (int i = 0; i < 8; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void F64(double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof(bits));
    U64(bits);
  }
  void Bytes(const uint8_t* data, size_t n) { out_.insert(out_.end(), data, data + n); }

 private:
  std::vector<uint8_t>& out_;
};

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  uint8_t U8() { return Has(1) ? data_[pos_++] : Fail<uint8_t>(); }
  uint32_t U32() {
    if (!Has(4)) return Fail<uint32_t>();
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t{data_[pos_++]} << (8 * i);
    return v;
  }
  int32_t I32() { return static_cast<int32_t>(U32()); }
  uint64_t U64() {
    if (!Has(8)) return Fail<uint64_t>();
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t{data_[pos_++]} << (8 * i);
    return v;
  }
  double F64() {
    const uint64_t bits = U64();
    double v;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  }
  // Returns a pointer to the next n bytes and skips them, or nullptr (and fails) if short.
  const uint8_t* Bytes(size_t n) {
    if (!Has(n)) return Fail<const uint8_t*>();
    const uint8_t* p = data_ + pos_;
    pos_ += n;
    return p;
  }

  bool failed() const { return failed_; }
  size_t position() const { return pos_; }
  size_t remaining() const { return size_ - pos_; }

 private:
  bool Has(size_t n) const { return !failed_ && n <= size_ - pos_; }
  template <typename T>
  T Fail() {
    failed_ = true;
    return T{};
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  bool failed_ = false;
};

}  // namespace fleetmap::core
