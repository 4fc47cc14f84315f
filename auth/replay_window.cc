#include "auth/replay_window.h"

namespace fleetmap::auth {

bool ReplayWindow::Accept(uint64_t seq) {
  if (!any_ || seq > highest_) {
    const uint64_t shift = any_ ? seq - highest_ : kWindow;
    seen_ = shift >= kWindow ? std::bitset<kWindow>() : seen_ << shift;
    seen_.set(0);
    highest_ = seq;
    any_ = true;
    return true;
  }
  const uint64_t age = highest_ - seq;
  if (age >= kWindow || seen_.test(age)) return false;
  seen_.set(age);
  return true;
}

}  // namespace fleetmap::auth
