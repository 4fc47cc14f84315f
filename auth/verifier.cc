#include "auth/verifier.h"

#include "auth/trailer.h"

namespace fleetmap::auth {

const char* VerdictName(Verdict verdict) {
  switch (verdict) {
    case Verdict::kAccepted:
      return "accepted";
    case Verdict::kUnsigned:
      return "unsigned";
    case Verdict::kForged:
      return "forged";
    case Verdict::kWrongSender:
      return "wrong_sender";
    case Verdict::kReplayed:
      return "replayed";
  }
  return "unknown";
}

const char* RefusalText(Verdict verdict) {
  switch (verdict) {
    case Verdict::kAccepted:
      return "accepted";
    case Verdict::kUnsigned:
      return "an unsigned message refused: this fleet has a key";
    case Verdict::kForged:
      return "a message whose MAC is wrong (another key, or altered) refused";
    case Verdict::kWrongSender:
      return "a message signed by a sender that does not own this channel refused";
    case Verdict::kReplayed:
      return "a replayed message (its sequence number was seen before) refused";
  }
  return "refused";
}

std::vector<std::pair<std::string, int64_t>> Named(const AuthCounters& c) {
  return {{"auth_verified", c.auth_verified}, {"auth_unsigned", c.auth_unsigned},
          {"auth_forged", c.auth_forged},     {"auth_wrong_sender", c.auth_wrong_sender},
          {"auth_replayed", c.auth_replayed}, {"auth_unverified", c.auth_unverified}};
}

Verdict Verifier::Open(const std::string& channel, const void* data, int size,
                       const std::string& expected_sender, Opened* out) {
  Trailer t;
  const bool has_trailer = size > 0 && SplitTrailer(data, static_cast<size_t>(size), &t);
  if (!fleet_key_) {
    out->data = data;
    out->size = size;
    out->sender.clear();
    if (has_trailer) {
      ++counters_.auth_unverified;
      out->size = static_cast<int>(t.payload_size);
    }
    return Verdict::kAccepted;
  }
  if (!has_trailer || !t.has_mac()) {
    ++counters_.auth_unsigned;
    return Verdict::kUnsigned;
  }
  auto known = senders_.find(t.sender);
  const Key key =
      known != senders_.end() ? known->second.first : DeriveSenderKey(*fleet_key_, t.sender);
  if (!MacMatches(channel, t, key)) {
    ++counters_.auth_forged;
    return Verdict::kForged;
  }
  if (!expected_sender.empty() && t.sender != expected_sender) {
    ++counters_.auth_wrong_sender;
    return Verdict::kWrongSender;
  }
  if (known == senders_.end())
    known = senders_.emplace(t.sender, std::pair{key, ReplayWindow()}).first;
  if (!known->second.second.Accept(t.seq)) {
    ++counters_.auth_replayed;
    return Verdict::kReplayed;
  }
  ++counters_.auth_verified;
  out->data = t.payload;
  out->size = static_cast<int>(t.payload_size);
  out->sender = t.sender;
  return Verdict::kAccepted;
}

}  // namespace fleetmap::auth
