// Maps the scanner's clock (microseconds since power-up, an unsigned 32-bit counter that wraps
// every 71.6 minutes) to host time. Each telegram gives one pair (device time, host receive
// time); host - device = clock offset + transport latency, and latency is never negative, so
// the smallest difference over a recent window is the best offset estimate (it follows slow
// drift as old samples leave the window). A device restart (the counter jumps back by more
// than it could wrap) or a host clock step resets the estimate.
#pragma once

#include <cstdint>
#include <deque>

#include "core/result.h"

namespace fleetmap::drivers::sick {

struct DeviceClockOptions {
  int window_samples = 200;        // telegrams in the minimum window (200 = 13 s at 15 Hz); >= 1
  double max_offset_jump_s = 1.0;  // larger offset changes count as a clock step; > 0
  core::Status Validate() const;
};

class DeviceClock {
 public:
  explicit DeviceClock(DeviceClockOptions options = {});

  // Records one telegram and returns the host time of `device_time_us`.
  double Map(uint32_t device_time_us, double host_receive_s);
  // Host time of a device time without recording a sample (needs one Map call before).
  double ToHost(uint32_t device_time_us) const;

  double offset_s() const { return offset_s_; }
  int resets() const { return resets_; }

 private:
  int64_t Unwrap(uint32_t device_time_us) const;
  void Reset();

  const DeviceClockOptions options_;
  bool started_ = false;
  uint32_t last_raw_us_ = 0;
  int64_t wraps_ = 0;
  double offset_s_ = 0.0;
  int resets_ = 0;
  // (sample index, offset) with increasing offsets: front is the window minimum.
  std::deque<std::pair<int64_t, double>> window_;
  int64_t samples_ = 0;
};

}  // namespace fleetmap::drivers::sick
