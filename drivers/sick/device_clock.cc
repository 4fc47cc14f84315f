#include "drivers/sick/device_clock.h"

#include <cassert>
#include <cmath>

namespace fleetmap::drivers::sick {
namespace {

constexpr int64_t kWrapUs = int64_t{1} << 32;

}  // namespace

core::Status DeviceClockOptions::Validate() const {
  if (window_samples < 1) return core::InvalidArgument("device_clock.window_samples must be >= 1");
  if (!(max_offset_jump_s > 0.0)) {
    return core::InvalidArgument("device_clock.max_offset_jump_s must be positive");
  }
  return core::OkStatus();
}

DeviceClock::DeviceClock(DeviceClockOptions options) : options_(options) {
  assert(options_.Validate().ok());
}

int64_t DeviceClock::Unwrap(uint32_t device_time_us) const {
  int64_t wraps = wraps_;
  // A small step back past zero is a wrap; anything else going back is a restart (Map).
  if (started_ && device_time_us < last_raw_us_ && last_raw_us_ - device_time_us > kWrapUs / 2) {
    ++wraps;
  }
  return wraps * kWrapUs + device_time_us;
}

void DeviceClock::Reset() {
  window_.clear();
  wraps_ = 0;
  ++resets_;
}

double DeviceClock::Map(uint32_t device_time_us, double host_receive_s) {
  if (started_ && device_time_us < last_raw_us_ && last_raw_us_ - device_time_us <= kWrapUs / 2) {
    Reset();  // the counter went back: the scanner restarted
  } else if (started_ && device_time_us < last_raw_us_) {
    ++wraps_;
  }
  last_raw_us_ = device_time_us;
  const double device_s = static_cast<double>(wraps_ * kWrapUs + device_time_us) * 1e-6;
  const double offset = host_receive_s - device_s;
  if (started_ && !window_.empty() && std::abs(offset - offset_s_) > options_.max_offset_jump_s) {
    window_.clear();  // the host clock stepped: old samples no longer apply
    ++resets_;
  }
  started_ = true;
  while (!window_.empty() && window_.back().second >= offset) window_.pop_back();
  window_.emplace_back(samples_, offset);
  while (window_.front().first <= samples_ - options_.window_samples) window_.pop_front();
  ++samples_;
  offset_s_ = window_.front().second;
  return device_s + offset_s_;
}

double DeviceClock::ToHost(uint32_t device_time_us) const {
  return static_cast<double>(Unwrap(device_time_us)) * 1e-6 + offset_s_;
}

}  // namespace fleetmap::drivers::sick
