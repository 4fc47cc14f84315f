#include "auth/trailer.h"

#include <sodium.h>

#include <algorithm>
#include <cstring>

namespace fleetmap::auth {
namespace {

constexpr uint8_t kMagic[4] = {'F', 'M', 'A', '1'};
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

}  // namespace

void AppendTrailer(const std::string& channel, const std::string& sender, uint64_t seq,
                   const Key& key, std::vector<uint8_t>& message) {
  const std::string id = sender.substr(0, kMaxSenderBytes);
  message.insert(message.end(), id.begin(), id.end());
  message.push_back(static_cast<uint8_t>(id.size()));
  for (int shift = 56; shift >= 0; shift -= 8)
    message.push_back(static_cast<uint8_t>(seq >> shift));
  uint8_t mac[kMacBytes];
  ComputeMac(channel, message.data(), message.size(), key, mac);
  message.insert(message.end(), mac, mac + kMacBytes);
  message.insert(message.end(), kMagic, kMagic + 4);
}

bool SplitTrailer(const void* data, size_t size, Trailer* out) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (bytes == nullptr || size < kTrailerFixedBytes + 1) return false;
  if (std::memcmp(bytes + size - 4, kMagic, 4) != 0) return false;
  const size_t mac_at = size - 4 - kMacBytes;
  const size_t seq_at = mac_at - 8;
  const size_t n = bytes[seq_at - 1];
  if (n == 0 || n > kMaxSenderBytes || seq_at - 1 < n) return false;
  const size_t sender_at = seq_at - 1 - n;
  out->payload = bytes;
  out->payload_size = sender_at;
  out->sender.assign(reinterpret_cast<const char*>(bytes + sender_at), n);
  out->seq = 0;
  for (size_t i = 0; i < 8; ++i) out->seq = (out->seq << 8) | bytes[seq_at + i];
  out->mac = bytes + mac_at;
  out->signed_size = mac_at;
  return true;
}

bool MacMatches(const std::string& channel, const Trailer& trailer, const Key& key) {
  uint8_t mac[kMacBytes];
  ComputeMac(channel, trailer.payload, trailer.signed_size, key, mac);
  return sodium_memcmp(mac, trailer.mac, kMacBytes) == 0;
}

}  // namespace fleetmap::auth
