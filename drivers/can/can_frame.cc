#include "drivers/can/can_frame.h"

#include <cstdio>

namespace fleetmap::drivers::can {

bool IsValidFdLength(uint8_t len) {
  return len <= 8 || len == 12 || len == 16 || len == 20 || len == 24 || len == 32 || len == 48 ||
         len == 64;
}

core::Status CanFrame::Validate() const {
  const uint32_t mask =
      error ? kCanErrorClassMask : (extended ? kCanExtendedIdMask : kCanStandardIdMask);
  if (id & ~mask) return core::InvalidArgument("CAN id " + std::to_string(id) + " out of range");
  if (fd) {
    if (rtr) return core::InvalidArgument("CAN FD frames have no RTR");
    if (!IsValidFdLength(len)) {
      return core::InvalidArgument("CAN FD length " + std::to_string(len) + " is not valid");
    }
  } else if (len > 8) {
    return core::InvalidArgument("classic CAN length " + std::to_string(len) + " > 8");
  }
  if (len8_dlc != 0 && (fd || len != 8 || len8_dlc < 9 || len8_dlc > 15)) {
    return core::InvalidArgument("len8_dlc needs a classic 8-byte frame and a DLC of 9..15");
  }
  return core::OkStatus();
}

std::string CanFrame::ToString() const {
  char buf[16];
  std::snprintf(buf, sizeof(buf), extended || error ? "%08X" : "%03X",
                id | (error ? 0x20000000u : 0u));
  std::string s = buf;
  s += fd ? "##" : "#";
  if (fd) s.push_back("0123456789ABCDEF"[fd_flags & 0xF]);
  if (rtr) {
    s += "R";
    if (len > 0) s.push_back("0123456789ABCDEF"[len & 0xF]);
  } else {
    for (int i = 0; i < len; ++i) {
      std::snprintf(buf, sizeof(buf), "%02X", data[i]);
      s += buf;
    }
  }
  if (len8_dlc != 0) {
    s += "_";
    s.push_back("0123456789ABCDEF"[len8_dlc & 0xF]);
  }
  return s;
}

}  // namespace fleetmap::drivers::can
