// Spreads bursts of messages over time (a token bucket). A temporary map or a keyframe is a
// burst of tens to hundreds of tile messages; sent at once, they overflow whoever reads
// slowest: LCM queues at most 30 messages per subscription by default and drops the rest
// silently (lcm-logger does this), and a Wi-Fi link queues or loses them. Free of I/O: the
// caller asks how many messages it may send now and reports what it sent.
#pragma once
#include <algorithm>

#include "core/result.h"

namespace fleetmap::core {

struct PacerOptions {
  double rate_per_s = 400.0;  // sustained messages per second
  double burst = 16.0;        // messages that may go at once after a pause
  Status Validate() const {
    if (!(rate_per_s > 0.0) || !(burst >= 1.0))
      return InvalidArgument("pacer: rate_per_s must be > 0 and burst >= 1");
    return OkStatus();
  }
};

class SendPacer {
 public:
  explicit SendPacer(const PacerOptions& options = {})
      : options_(options), tokens_(options.burst) {}

  // How many messages may be sent at `now_s` (seconds, any monotonic clock).
  int Allowed(double now_s) {
    if (last_s_ >= 0.0 && now_s > last_s_)
      tokens_ = std::min(options_.burst, tokens_ + (now_s - last_s_) * options_.rate_per_s);
    last_s_ = std::max(last_s_, now_s);
    return static_cast<int>(tokens_ + 1e-9);  // 0.02 s * 100/s is 2, not 1.999...
  }
  void Sent(int messages) { tokens_ = std::max(0.0, tokens_ - messages); }

 private:
  PacerOptions options_;
  double tokens_;
  double last_s_ = -1.0;
};

}  // namespace fleetmap::core
