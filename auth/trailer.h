// The authentication trailer: appended to a message's LCM encoding, so the message itself
// is unchanged. lcm-spy, lcm-logger and any LCM decoder read the message and never look past
// its last field; our receivers split the trailer off and check it (docs/security.md).
//
//   message bytes | sender (n bytes) | n (u8) | seq (u64, big-endian) | MAC (32) | "FMA1"
//
// MAC = HMAC-SHA-256 (libsodium crypto_auth_hmacsha256) with the sender's key over
// "fleetmap-auth-1", the channel name (u16 length first), and every byte before the MAC: the
// channel binds a message to where it was sent, so it cannot be moved to another channel.
//
// A fleet without a key still names who sent what, with an identity trailer (no MAC):
//
//   message bytes | sender (n bytes) | n (u8) | seq (u64, big-endian) | "FMI1"
//
// so that a reader of a log can tell the aggregator's word from other traffic on the same
// channel (a second fleet, a test tool, a misconfigured process). It proves nothing against
// someone who means harm: that takes the key.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "auth/key.h"

namespace fleetmap::auth {

constexpr size_t kMacBytes = 32;
constexpr size_t kMaxSenderBytes = 64;
// Trailer size without the sender id: n, seq, MAC, magic.
constexpr size_t kTrailerFixedBytes = 1 + 8 + kMacBytes + 4;
// Identity trailer size without the sender id: n, seq, magic.
constexpr size_t kIdentityTrailerFixedBytes = 1 + 8 + 4;

// A message with its trailer split off. Pointers point into the received bytes.
struct Trailer {
  const uint8_t* payload = nullptr;  // the message's LCM encoding
  size_t payload_size = 0;
  std::string sender;
  uint64_t seq = 0;
  const uint8_t* mac = nullptr;  // kMacBytes; null for an identity trailer
  size_t signed_size = 0;        // bytes the MAC covers after the channel: up to the MAC
  bool has_mac() const { return mac != nullptr; }
};

// Appends the trailer for `sender` (1..64 bytes) and `seq` to `message`, signed with `key`.
void AppendTrailer(const std::string& channel, const std::string& sender, uint64_t seq,
                   const Key& key, std::vector<uint8_t>& message);
// Appends the identity trailer for `sender` (1..64 bytes) and `seq`: no MAC.
void AppendIdentityTrailer(const std::string& sender, uint64_t seq, std::vector<uint8_t>& message);
// Splits either trailer off `data`; false when the bytes end with none (a message that names
// no sender).
bool SplitTrailer(const void* data, size_t size, Trailer* out);
// The size of the LCM message in `data`: `size` less its trailer, if it has one. For readers
// of logs that decode what was sent and need not know who sent it.
size_t PayloadSize(const void* data, size_t size);
// True if the trailer's MAC is right for `channel` under `key` (constant-time compare); false
// for an identity trailer.
bool MacMatches(const std::string& channel, const Trailer& trailer, const Key& key);

}  // namespace fleetmap::auth
