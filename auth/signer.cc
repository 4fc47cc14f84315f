#include "auth/signer.h"

#include <cmath>

#include "auth/trailer.h"

namespace fleetmap::auth {

uint64_t FirstSequence(double wall_s) {
  const double us = std::floor(std::max(0.0, wall_s) * 1e6);
  return static_cast<uint64_t>(us) << 10;
}

Signer::Signer(const std::optional<Key>& fleet_key, std::string sender, uint64_t first_seq)
    : sender_(std::move(sender)), next_seq_(first_seq) {
  if (fleet_key) key_ = DeriveSenderKey(*fleet_key, sender_);
}

void Signer::Seal(const std::string& channel, std::vector<uint8_t>& message) {
  if (key_) {
    AppendTrailer(channel, sender_, next_seq_++, *key_, message);
  } else if (!sender_.empty()) {
    AppendIdentityTrailer(sender_, next_seq_++, message);
  }
}

}  // namespace fleetmap::auth
