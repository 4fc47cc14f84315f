// A sliding window over one sender's sequence numbers (as in IPsec, RFC 4303 3.4.3): the
// highest number seen and which of the kWindow numbers below it were seen. A number seen
// before, or older than the window, is a replay. Gaps are normal (a receiver reads only some
// of a sender's channels) and so is mild reordering across channels.
#pragma once

#include <bitset>
#include <cstdint>

namespace fleetmap::auth {

class ReplayWindow {
 public:
  static constexpr uint64_t kWindow = 1024;
  // True, and remembered, if `seq` is new; false for a replay or a number below the window.
  bool Accept(uint64_t seq);
  uint64_t highest() const { return highest_; }

 private:
  bool any_ = false;
  uint64_t highest_ = 0;
  std::bitset<kWindow> seen_;  // bit i: highest_ - i was seen
};

}  // namespace fleetmap::auth
