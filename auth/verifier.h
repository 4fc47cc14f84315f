// The receiving side: splits the trailer off a message and decides whether to believe it.
// With a fleet key, a message is accepted only if it carries a trailer, its MAC is right
// under its sender's key, its sender is the one the channel belongs to, and its sequence
// number is new for that sender (replay_window.h); an identity trailer (no MAC) is unsigned.
// Without a key, either trailer is split off unchecked and everything is accepted, as before
// authentication existed.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "auth/key.h"
#include "auth/replay_window.h"

namespace fleetmap::auth {

enum class Verdict { kAccepted, kUnsigned, kForged, kWrongSender, kReplayed };
const char* VerdictName(Verdict verdict);  // "accepted", "unsigned", ...
// Why a message was refused, in words for a log line.
const char* RefusalText(Verdict verdict);

struct AuthCounters {
  int64_t auth_verified = 0;      // accepted with a key: MAC, sender and sequence right
  int64_t auth_unsigned = 0;      // no MAC (no trailer, or an identity one) while keyed
  int64_t auth_forged = 0;        // a trailer whose MAC is wrong (another key, altered bytes)
  int64_t auth_wrong_sender = 0;  // a right MAC, but the sender does not own the channel
  int64_t auth_replayed = 0;      // a sequence number seen before or older than the window
  int64_t auth_unverified = 0;    // no key configured: a trailer split off unchecked
};
// Every counter with its field name, in declaration order.
std::vector<std::pair<std::string, int64_t>> Named(const AuthCounters& c);

// A message accepted by the verifier. `data` points into the received bytes.
struct Opened {
  const void* data = nullptr;
  int size = 0;
  std::string sender;  // empty for an unsigned message (no key configured)
};

class Verifier {
 public:
  explicit Verifier(std::optional<Key> fleet_key = std::nullopt)
      : fleet_key_(std::move(fleet_key)) {}

  bool enabled() const { return fleet_key_.has_value(); }
  // `expected_sender`: the only sender allowed on this channel; empty: any sender of the
  // fleet (the caller then checks the message's own fields against Opened::sender).
  Verdict Open(const std::string& channel, const void* data, int size,
               const std::string& expected_sender, Opened* out);
  const AuthCounters& counters() const { return counters_; }

 private:
  std::optional<Key> fleet_key_;
  // Only senders whose MAC was right get an entry: the fleet's members, a bounded set.
  std::map<std::string, std::pair<Key, ReplayWindow>> senders_;
  AuthCounters counters_;
};

}  // namespace fleetmap::auth
