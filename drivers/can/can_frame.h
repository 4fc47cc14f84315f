// One CAN frame as the drivers pass it around: classic CAN (up to 8 bytes) or CAN FD (up to
// 64), standard (11-bit) or extended (29-bit) identifier, remote request or error frame,
// with the time it was received. Independent of the SocketCAN headers.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/result.h"

namespace fleetmap::drivers::can {

constexpr uint32_t kCanStandardIdMask = 0x7FF;
constexpr uint32_t kCanExtendedIdMask = 0x1FFFFFFF;
constexpr uint32_t kCanErrorClassMask = 0x1FFFFFFF;
constexpr uint8_t kCanFdBitRateSwitch = 0x01;        // BRS
constexpr uint8_t kCanFdErrorStateIndicator = 0x02;  // ESI

struct CanFrame {
  uint32_t id = 0;        // without flags; for an error frame the error class bits
  bool extended = false;  // 29-bit identifier
  bool rtr = false;       // remote transmission request (classic CAN only)
  bool error = false;     // error frame reported by the controller
  bool fd = false;        // CAN FD frame
  uint8_t fd_flags = 0;   // kCanFdBitRateSwitch | kCanFdErrorStateIndicator
  uint8_t len = 0;        // data bytes (RTR: the requested length)
  uint8_t len8_dlc = 0;   // classic CAN with 8 bytes: the raw DLC 9..15 if sent so, else 0
  std::array<uint8_t, 64> data{};
  double stamp_s = 0.0;  // receive time (kernel timestamp or log time), seconds since epoch

  // Identifier range, length (0..8 classic; FD: 0..8, 12, 16, 20, 24, 32, 48, 64), no RTR on
  // FD, len8_dlc only with len 8.
  core::Status Validate() const;
  std::string ToString() const;  // candump style "123#1122"
};

bool IsValidFdLength(uint8_t len);

}  // namespace fleetmap::drivers::can
