// Keys: the fleet key that a deployment shares, read from a file that only its owner can
// read, and the per-sender keys derived from it (docs/security.md).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/result.h"

namespace fleetmap::auth {

constexpr size_t kKeyBytes = 32;

// A 256-bit secret. Wiped when destroyed.
class Key {
 public:
  Key() { bytes_.fill(0); }
  explicit Key(const std::array<uint8_t, kKeyBytes>& bytes) : bytes_(bytes) {}
  Key(const Key&) = default;
  Key& operator=(const Key&) = default;
  ~Key();
  const uint8_t* data() const { return bytes_.data(); }

 private:
  std::array<uint8_t, kKeyBytes> bytes_;
};

// Reads a key file: 64 hexadecimal digits (surrounding whitespace allowed), as made by
// `fleetmap-keygen` or `(umask 077; od -An -tx1 -N32 /dev/urandom | tr -d ' \n' > F)`.
// Refuses, with an error that says how to fix it, a file that its group or others may read
// or write (chmod 600), one that is not a regular file, and anything but 32 bytes of hex.
core::Result<Key> ReadKeyFile(const std::string& path);
// The same text, for tests and the key generator.
core::Result<Key> ParseKeyText(const std::string& text);
std::string KeyToHex(const Key& key);
// libsodium's sodium_init, once; aborts if the system has no random source.
void InitSodium();

// A new random key (libsodium's randombytes).
Key GenerateKey();

// The key a sender (a vehicle id, or the aggregator's process name) signs with: keyed
// BLAKE2b (crypto_generichash, the primitive behind crypto_kdf) of a domain string and the
// id, keyed with the fleet key. crypto_kdf_derive_from_key itself takes a 64-bit number, and
// our senders are named by strings.
Key DeriveSenderKey(const Key& fleet_key, const std::string& sender);

}  // namespace fleetmap::auth
