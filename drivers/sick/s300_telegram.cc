#include "drivers/sick/s300_telegram.h"

#include <array>
#include <cmath>
#include <limits>

namespace fleetmap::drivers::sick {
namespace {

uint16_t Be16(const uint8_t* p) { return static_cast<uint16_t>((p[0] << 8) | p[1]); }
void PutBe16(std::vector<uint8_t>& out, uint16_t v) {
  out.push_back(static_cast<uint8_t>(v >> 8));
  out.push_back(static_cast<uint8_t>(v));
}
void PutLe16(std::vector<uint8_t>& out, uint16_t v) {
  out.push_back(static_cast<uint8_t>(v));
  out.push_back(static_cast<uint8_t>(v >> 8));
}

// The fixed bytes that start every telegram: four zeros, two zeros, (size), FF.
bool HeaderMatches(const uint8_t* p, size_t available) {
  static const int kFixed[] = {0, 0, 0, 0, 0, 0, -1, -1, 0xFF};
  for (size_t i = 0; i < 9 && i < available; ++i) {
    if (kFixed[i] >= 0 && p[i] != kFixed[i]) return false;
  }
  return true;
}

size_t TotalBytes(uint16_t size_words) { return 4 + 2 * size_t{size_words}; }
constexpr size_t kMaxTotalBytes = kS300HeaderBytes + 2 * kS300MaxBeams + 2;

// CRC-16/CCITT (polynomial 0x1021, MSB first) one byte at a time: entry b is the bitwise
// update of a CRC whose top byte is b. Eight times fewer steps than bit by bit.
std::array<uint16_t, 256> MakeCrc16Table() {
  std::array<uint16_t, 256> table{};
  for (int byte = 0; byte < 256; ++byte) {
    uint16_t crc = static_cast<uint16_t>(byte << 8);
    for (int b = 0; b < 8; ++b) {
      crc = (crc & 0x8000) ? static_cast<uint16_t>((crc << 1) ^ 0x1021)
                           : static_cast<uint16_t>(crc << 1);
    }
    table[static_cast<size_t>(byte)] = crc;
  }
  return table;
}

}  // namespace

uint16_t Crc16Ccitt(const uint8_t* data, size_t size, uint16_t crc) {
  static const std::array<uint16_t, 256> kTable = MakeCrc16Table();
  for (size_t i = 0; i < size; ++i) {
    crc = static_cast<uint16_t>((crc << 8) ^ kTable[((crc >> 8) ^ data[i]) & 0xFF]);
  }
  return crc;
}

std::vector<uint8_t> EncodeS300Telegram(const S300Telegram& t) {
  std::vector<uint8_t> out(6, 0);
  const size_t total = kS300HeaderBytes + 2 * t.beams.size() + 2;
  PutBe16(out, static_cast<uint16_t>((total - 4) / 2));
  out.push_back(0xFF);
  out.push_back(t.device_address);
  PutBe16(out, t.protocol_version);
  PutBe16(out, t.status);
  PutBe16(out, static_cast<uint16_t>(t.scan_number >> 16));
  PutBe16(out, static_cast<uint16_t>(t.scan_number));
  PutBe16(out, t.telegram_number);
  PutBe16(out, t.block_type);
  PutBe16(out, t.measurement_range);
  for (const uint16_t w : t.beams) PutLe16(out, w);
  PutLe16(out, Crc16Ccitt(out.data() + 4, out.size() - 4));
  return out;
}

core::Result<S300Telegram> ParseS300Telegram(const uint8_t* p, size_t size) {
  if (size < kS300HeaderBytes + 2) return core::DataLoss("S300 telegram shorter than a header");
  if (!HeaderMatches(p, size)) return core::InvalidArgument("S300 telegram header is wrong");
  const size_t total = TotalBytes(Be16(p + 6));
  if (total != size || total > kMaxTotalBytes || (total - kS300HeaderBytes) % 2 != 0) {
    return core::DataLoss("S300 size field says " + std::to_string(total) + " bytes, got " +
                          std::to_string(size));
  }
  const uint16_t crc = static_cast<uint16_t>(p[size - 2] | (p[size - 1] << 8));
  if (Crc16Ccitt(p + 4, size - 6) != crc) return core::DataLoss("S300 telegram CRC mismatch");
  S300Telegram t;
  t.device_address = p[9];
  t.protocol_version = Be16(p + 10);
  t.status = Be16(p + 12);
  t.scan_number = (uint32_t{Be16(p + 14)} << 16) | Be16(p + 16);
  t.telegram_number = Be16(p + 18);
  t.block_type = Be16(p + 20);
  t.measurement_range = Be16(p + 22);
  const size_t beams = (size - kS300HeaderBytes - 2) / 2;
  t.beams.resize(beams);
  for (size_t i = 0; i < beams; ++i) {
    const uint8_t* b = p + kS300HeaderBytes + 2 * i;
    t.beams[i] = static_cast<uint16_t>(b[0] | (b[1] << 8));
  }
  return t;
}

core::Status S300ScanOptions::Validate() const {
  if (!(field_of_view_rad > 0.0 && field_of_view_rad <= 2 * M_PI)) {
    return core::InvalidArgument("s300.field_of_view_rad must be in (0, 2 pi]");
  }
  if (!(range_min_m >= 0.0 && range_max_m > range_min_m)) {
    return core::InvalidArgument("s300.range_max_m must exceed range_min_m >= 0");
  }
  return core::OkStatus();
}

core::Result<core::LaserScan> S300ToLaserScan(const S300Telegram& t, const S300ScanOptions& o,
                                              double stamp_s) {
  if (t.block_type != kS300DistanceBlock) {
    return core::InvalidArgument("S300 telegram is not a distance block");
  }
  if (t.beams.size() < 2) return core::InvalidArgument("S300 telegram has fewer than 2 beams");
  core::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.angle_min_rad = -o.field_of_view_rad / 2.0;
  scan.angle_increment_rad = o.field_of_view_rad / static_cast<double>(t.beams.size() - 1);
  scan.range_min_m = o.range_min_m;
  scan.range_max_m = o.range_max_m;
  scan.ranges_m.resize(t.beams.size());
  for (size_t i = 0; i < t.beams.size(); ++i) {
    const uint16_t cm = S300Telegram::DistanceCm(t.beams[i]);
    scan.ranges_m[i] = cm == 0 ? std::numeric_limits<float>::infinity() : cm * 0.01f;
  }
  return scan;
}

void S300StreamSplitter::Feed(const uint8_t* data, size_t size) {
  if (start_ > 0) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
  buffer_.insert(buffer_.end(), data, data + size);
}

void S300StreamSplitter::Skip(size_t n) {
  stats_.garbage_bytes += n;
  start_ += n;
}

std::optional<S300Telegram> S300StreamSplitter::Next() {
  while (buffered_bytes() > 0) {
    const uint8_t* p = buffer_.data() + start_;
    const size_t available = buffered_bytes();
    if (!HeaderMatches(p, available)) {
      Skip(1);
      continue;
    }
    if (available < kS300HeaderBytes) return std::nullopt;
    const size_t total = TotalBytes(Be16(p + 6));
    if (total < kS300HeaderBytes + 2 || total > kMaxTotalBytes) {
      ++stats_.bad_size;
      Skip(1);
      continue;
    }
    if (available < total) return std::nullopt;
    core::Result<S300Telegram> t = ParseS300Telegram(p, total);
    if (!t.ok()) {
      ++stats_.bad_crc;
      Skip(1);
      continue;
    }
    start_ += total;
    ++stats_.telegrams;
    return std::move(t).value();
  }
  return std::nullopt;
}

}  // namespace fleetmap::drivers::sick
