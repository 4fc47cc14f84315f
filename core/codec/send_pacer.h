// Spreads bursts of messages over time (token buckets, one for messages and one for bytes). A
// temporary map or a keyframe is a burst of tens to hundreds of tile messages; sent at once,
// they overflow whoever reads slowest: LCM queues at most 30 messages per subscription by
// default and drops the rest silently (lcm-logger does this), and a Wi-Fi link queues or
// loses them. The byte budget keeps a link within its share of the channel whatever the size
// of the messages. Free of I/O: the caller asks whether it may send now and reports what it
// sent.
#pragma once
#include <algorithm>
#include <cstddef>

#include "core/result.h"

namespace fleetmap::core {

struct PacerOptions {
  double rate_per_s = 400.0;     // sustained messages per second
  double burst = 16.0;           // messages that may go at once after a pause
  double bytes_per_s = 0.0;      // sustained bytes per second; 0: no byte budget
  double burst_bytes = 16384.0;  // bytes that may go at once after a pause
  Status Validate() const {
    if (!(rate_per_s > 0.0) || !(burst >= 1.0))
      return InvalidArgument("pacer: rate_per_s must be > 0 and burst >= 1");
    if (!(bytes_per_s >= 0.0) || !(burst_bytes >= 1.0))
      return InvalidArgument("pacer: bytes_per_s must be >= 0 and burst_bytes >= 1");
    return OkStatus();
  }
};

class SendPacer {
 public:
  explicit SendPacer(const PacerOptions& options = {})
      : options_(options), tokens_(options.burst), bytes_(options.burst_bytes) {}

  // How many messages may be sent at `now_s` (seconds, any monotonic clock), the byte budget
  // aside.
  int Allowed(double now_s) {
    Refill(now_s);
    return static_cast<int>(tokens_ + 1e-9);  // 0.02 s * 100/s is 2, not 1.999...
  }
  // Bytes the byte budget allows at `now_s` (0 while a large message's debt is paid back);
  // unlimited without one.
  double BytesAllowed(double now_s) const {
    if (options_.bytes_per_s <= 0.0) return 1e18;
    const double elapsed = last_s_ >= 0.0 && now_s > last_s_ ? now_s - last_s_ : 0.0;
    return std::max(0.0, std::min(options_.burst_bytes, bytes_ + elapsed * options_.bytes_per_s));
  }
  // One more message may go now: within both budgets (a message larger than the bytes left
  // goes when any are left, and the budget then runs into debt).
  bool MaySend(double now_s) { return Allowed(now_s) > 0 && BytesAllowed(now_s) > 0.0; }
  void Sent(int messages, size_t bytes = 0) {
    tokens_ = std::max(0.0, tokens_ - messages);
    bytes_ -= static_cast<double>(bytes);
  }

 private:
  void Refill(double now_s) {
    if (last_s_ >= 0.0 && now_s > last_s_) {
      tokens_ = std::min(options_.burst, tokens_ + (now_s - last_s_) * options_.rate_per_s);
      bytes_ = std::min(options_.burst_bytes, bytes_ + (now_s - last_s_) * options_.bytes_per_s);
    }
    last_s_ = std::max(last_s_, now_s);
  }

  PacerOptions options_;
  double tokens_;
  double bytes_;  // negative: a debt
  double last_s_ = -1.0;
};

}  // namespace fleetmap::core
