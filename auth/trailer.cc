#include "auth/trailer.h"

#include <sodium.h>

#include <algorithm>
#include <cstring>

namespace fleetmap::auth {
namespace {

constexpr uint8_t kMagic[4] = {'F', 'M', 'A', '1'};
constexpr uint8_t kIdentityMagic[4] = {'F', 'M', 'I', '1'};
constexpr const char* kMacDomain = "fleetmap-auth-1";

void ComputeMac(const std::string& channel, const uint8_t* signed_bytes, size_t signed_size,
                const Key& key, uint8_t* mac) {
  InitSodium();
  crypto_auth_hmacsha256_state state;
  crypto_auth_hmacsha256_init(&state, key.data(), kKeyBytes);
  crypto_auth_hmacsha256_update(&state, reinterpret_cast<const uint8_t*>(kMacDomain),
                                std::strlen(kMacDomain));
  const uint16_t n = static_cast<uint16_t>(std::min<size_t>(channel.size(), 0xffff));
  const uint8_t len[2] = {static_cast<uint8_t>(n >> 8), static_cast<uint8_t>(n & 0xff)};
  crypto_auth_hmacsha256_update(&state, len, 2);
  crypto_auth_hmacsha256_update(&state, reinterpret_cast<const uint8_t*>(channel.data()), n);
  crypto_auth_hmacsha256_update(&state, signed_bytes, signed_size);
  crypto_auth_hmacsha256_final(&state, mac);
  sodium_memzero(&state, sizeof state);
}

void AppendSenderAndSequence(const std::string& sender, uint64_t seq,
                             std::vector<uint8_t>& message) {
  const std::string id = sender.substr(0, kMaxSenderBytes);
  message.insert(message.end(), id.begin(), id.end());
  message.push_back(static_cast<uint8_t>(id.size()));
  for (int shift = 56; shift >= 0; shift -= 8)
    message.push_back(static_cast<uint8_t>(seq >> shift));
}

// Reads sender and sequence that end at `end` (the MAC or the magic): false if the sender's
// length does not fit.
bool ReadSenderAndSequence(const uint8_t* bytes, size_t end, Trailer* out) {
  const size_t seq_at = end - 8;
  const size_t n = bytes[seq_at - 1];
  if (n == 0 || n > kMaxSenderBytes || seq_at - 1 < n) return false;
  const size_t sender_at = seq_at - 1 - n;
  out->payload = bytes;
  out->payload_size = sender_at;
  out->sender.assign(reinterpret_cast<const char*>(bytes + sender_at), n);
  out->seq = 0;
  for (size_t i = 0; i < 8; ++i) out->seq = (out->seq << 8) | bytes[seq_at + i];
  return true;
}

}  // namespace

void AppendTrailer(const std::string& channel, const std::string& sender, uint64_t seq,
                   const Key& key, std::vector<uint8_t>& message) {
  AppendSenderAndSequence(sender, seq, message);
  uint8_t mac[kMacBytes];
  ComputeMac(channel, message.data(), message.size(), key, mac);
  message.insert(message.end(), mac, mac + kMacBytes);
  message.insert(message.end(), kMagic, kMagic + 4);
}

void AppendIdentityTrailer(const std::string& sender, uint64_t seq, std::vector<uint8_t>& message) {
  AppendSenderAndSequence(sender, seq, message);
  message.insert(message.end(), kIdentityMagic, kIdentityMagic + 4);
}

bool SplitTrailer(const void* data, size_t size, Trailer* out) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (bytes == nullptr || size < kIdentityTrailerFixedBytes + 1) return false;
  const uint8_t* magic = bytes + size - 4;
  if (std::memcmp(magic, kIdentityMagic, 4) == 0) {
    if (!ReadSenderAndSequence(bytes, size - 4, out)) return false;
    out->mac = nullptr;
    out->signed_size = 0;
    return true;
  }
  if (size < kTrailerFixedBytes + 1 || std::memcmp(magic, kMagic, 4) != 0) return false;
  const size_t mac_at = size - 4 - kMacBytes;
  if (!ReadSenderAndSequence(bytes, mac_at, out)) return false;
  out->mac = bytes + mac_at;
  out->signed_size = mac_at;
  return true;
}

size_t PayloadSize(const void* data, size_t size) {
  Trailer t;
  return SplitTrailer(data, size, &t) ? t.payload_size : size;
}

bool MacMatches(const std::string& channel, const Trailer& trailer, const Key& key) {
  if (!trailer.has_mac()) return false;
  uint8_t mac[kMacBytes];
  ComputeMac(channel, trailer.payload, trailer.signed_size, key, mac);
  return sodium_memcmp(mac, trailer.mac, kMacBytes) == 0;
}

}  // namespace fleetmap::auth
