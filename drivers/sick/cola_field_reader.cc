#include "drivers/sick/cola_field_reader.h"

namespace fleetmap::drivers::sick {
namespace {

// Hex digits to a value; false on an empty, over-long or non-hex token.
bool ParseHex(std::string_view t, uint64_t& value) {
  if (t.empty() || t.size() > 16) return false;
  value = 0;
  for (const char c : t) {
    int d;
    if (c >= '0' && c <= '9') {
      d = c - '0';
    } else if (c >= 'A' && c <= 'F') {
      d = c - 'A' + 10;
    } else if (c >= 'a' && c <= 'f') {
      d = c - 'a' + 10;
    } else {
      return false;
    }
    value = (value << 4) | static_cast<uint64_t>(d);
  }
  return true;
}

bool ParseDecimal(std::string_view t, uint64_t& value) {
  if (t.empty() || t.size() > 19) return false;
  value = 0;
  for (const char c : t) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<uint64_t>(c - '0');
  }
  return true;
}

}  // namespace

std::string_view AsciiFieldReader::Token() {
  if (failed_) return {};
  if (pos_ < s_.size() && s_[pos_] == ' ') ++pos_;  // the separator before this token
  const size_t begin = pos_;
  while (pos_ < s_.size() && s_[pos_] != ' ') ++pos_;
  if (pos_ == begin) Fail();
  return s_.substr(begin, pos_ - begin);
}

uint64_t AsciiFieldReader::Unsigned(uint64_t max) {
  const std::string_view t = Token();
  uint64_t v = 0;
  const bool ok = t.size() > 1 && t[0] == '+' ? ParseDecimal(t.substr(1), v) : ParseHex(t, v);
  if (!ok || v > max) return Fail();
  return v;
}

int32_t AsciiFieldReader::I32() {
  const std::string_view t = Token();
  uint64_t v = 0;
  if (t.size() > 1 && (t[0] == '+' || t[0] == '-')) {
    if (!ParseDecimal(t.substr(1), v) || v > 0x80000000u) return static_cast<int32_t>(Fail());
    const int64_t s = t[0] == '-' ? -static_cast<int64_t>(v) : static_cast<int64_t>(v);
    if (s > INT32_MAX) return static_cast<int32_t>(Fail());
    return static_cast<int32_t>(s);
  }
  if (!ParseHex(t, v) || v > 0xFFFFFFFFu) return static_cast<int32_t>(Fail());
  return static_cast<int32_t>(static_cast<uint32_t>(v));
}

std::string AsciiFieldReader::String8() {
  const size_t n = U8();
  if (failed_) return {};
  if (pos_ >= s_.size() || s_[pos_] != ' ' || s_.size() - pos_ - 1 < n) {
    Fail();
    return {};
  }
  std::string out(s_.substr(pos_ + 1, n));
  pos_ += 1 + n;
  return out;
}

bool AsciiFieldReader::Values(uint16_t* out, size_t n, uint32_t max) {
  for (size_t i = 0; i < n; ++i) {
    out[i] = static_cast<uint16_t>(Unsigned(max));
    if (failed_) return false;
  }
  return true;
}

}  // namespace fleetmap::drivers::sick
