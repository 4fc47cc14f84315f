// The continuous data output of the SICK S300/S3000 safety scanners over RS-422 (as the
// public cob_sick_s300 driver reads it; protocol 1.02 framing):
//   0  00 00 00 00       reply header
//   4  00 00             trigger result
//   6  u16 big-endian    size: 16-bit words from byte 4 up to and including the CRC
//   8  FF                coordination flag
//   9  u8                device address (7 by default)
//   10 u16 big-endian    protocol version (0x0102)
//   12 u16 big-endian    status (0 = normal)
//   14 u32 big-endian    scan number
//   18 u16 big-endian    telegram number
//   20 BB BB             block type: distances (AA AA I/O, CC CC reflector marks)
//   22 11 11             measurement range 1
//   24 u16 little-endian per beam: bits 0-12 distance in cm, bit 13 reflector,
//                        bit 14 protective field infringed, bit 15 warning field infringed
//   .. u16 little-endian CRC-16/CCITT (poly 0x1021, init 0xFFFF) over bytes 4 up to the CRC
// S300: 541 beams over 270 degrees (0.5 degree); S3000: 381 beams over 190 degrees.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/result.h"
#include "core/scan.h"

namespace fleetmap::drivers::sick {

// CRC-16/CCITT-FALSE: check value 0x29B1 for "123456789".
uint16_t Crc16Ccitt(const uint8_t* data, size_t size, uint16_t crc = 0xFFFF);

constexpr size_t kS300HeaderBytes = 24;
constexpr uint16_t kS300DistanceBlock = 0xBBBB;
constexpr size_t kS300MaxBeams = 2000;

struct S300Telegram {
  uint8_t device_address = 7;
  uint16_t protocol_version = 0x0102;
  uint16_t status = 0;
  uint32_t scan_number = 0;
  uint16_t telegram_number = 0;
  uint16_t block_type = kS300DistanceBlock;
  uint16_t measurement_range = 0x1111;
  std::vector<uint16_t> beams;  // raw words, see above

  static uint16_t DistanceCm(uint16_t word) { return word & 0x1FFF; }
  static bool Reflector(uint16_t word) { return word & 0x2000; }
  static bool ProtectiveField(uint16_t word) { return word & 0x4000; }
  static bool WarningField(uint16_t word) { return word & 0x8000; }
};

std::vector<uint8_t> EncodeS300Telegram(const S300Telegram& telegram);
// Parses exactly one telegram (DataLoss on a bad CRC or size, InvalidArgument on a bad header).
core::Result<S300Telegram> ParseS300Telegram(const uint8_t* data, size_t size);

struct S300ScanOptions {
  double field_of_view_rad = 4.71238898038469;  // 270 degrees (S300); 190 degrees for S3000
  double range_min_m = 0.05;
  double range_max_m = 30.0;  // distances are 13 bits of cm: at most 81.91 m
  core::Status Validate() const;
};
// Beams spread evenly over the field of view, centred ahead; distance 0 becomes +infinity.
core::Result<core::LaserScan> S300ToLaserScan(const S300Telegram& telegram,
                                              const S300ScanOptions& options, double stamp_s);

struct S300SplitterStats {
  uint64_t telegrams = 0;
  uint64_t garbage_bytes = 0;
  uint64_t bad_crc = 0;
  uint64_t bad_size = 0;
};

// Cuts a serial byte stream into S300 telegrams, resynchronising on the next header after
// garbage or a bad CRC; buffers at most one maximal telegram plus one Feed call.
class S300StreamSplitter {
 public:
  void Feed(const uint8_t* data, size_t size);
  std::optional<S300Telegram> Next();
  const S300SplitterStats& stats() const { return stats_; }
  size_t buffered_bytes() const { return buffer_.size() - start_; }

 private:
  void Skip(size_t n);
  std::vector<uint8_t> buffer_;
  size_t start_ = 0;
  S300SplitterStats stats_;
};

}  // namespace fleetmap::drivers::sick
