// What a process signs its messages with: its sender id, its key (derived from the fleet
// key) and a sequence number that rises by one per message. Without a fleet key it still
// names the sender and the sequence number (an identity trailer, trailer.h), unsigned.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "auth/key.h"

namespace fleetmap::auth {

// The first sequence number of a process started at `wall_s` (seconds since the Unix epoch):
// its microseconds times 1024. Receivers remember the highest number per sender, so a
// restarted sender must start above where it stopped; it does while its clock does not go
// back across the restart and it sent fewer than 1024 messages per microsecond of its life.
uint64_t FirstSequence(double wall_s);

class Signer {
 public:
  Signer() = default;  // appends nothing
  Signer(const std::optional<Key>& fleet_key, std::string sender, uint64_t first_seq);

  bool enabled() const { return key_.has_value(); }
  const std::string& sender() const { return sender_; }
  // Appends the trailer (trailer.h) for `channel`; without a key the identity trailer.
  void Seal(const std::string& channel, std::vector<uint8_t>& message);

 private:
  std::optional<Key> key_;
  std::string sender_;
  uint64_t next_seq_ = 0;
};

}  // namespace fleetmap::auth
