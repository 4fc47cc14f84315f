// Whose word counts in a log: a message on a channel that belongs to a process is read only
// if its trailer (auth/trailer.h) names that process with a sequence number not seen before
// from it, and, with the fleet key, only if its MAC is right. A log holds everything on the
// multicast groups, so another fleet, a test tool or a copy of an old message would otherwise
// change the figures.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "auth/key.h"
#include "auth/replay_window.h"
#include "auth/verifier.h"

namespace fleetmap::eval::recording {

// A message's LCM encoding: the logged bytes, and once attributed the same without the trailer.
struct Payload {
  const void* data = nullptr;
  int size = 0;
};

class SenderAttribution {
 public:
  explicit SenderAttribution(std::optional<auth::Key> fleet_key)
      : verifier_(std::move(fleet_key)) {}

  // Null if the message on `channel` is `owner`'s (any fleet member's when `owner` is empty),
  // and `p` then holds it without its trailer; else the reason it is not, and `p` is
  // unchanged: auth::VerdictName, or without the fleet key "unnamed" (no trailer names a
  // sender). The sequence numbers accepted are remembered: one call per message, in log order.
  const char* Attribute(const std::string& channel, const std::string& owner, Payload* p);

 private:
  auth::Verifier verifier_;                            // with the fleet key, if there is one
  std::map<std::string, auth::ReplayWindow> windows_;  // without it: per named sender
};

}  // namespace fleetmap::eval::recording
