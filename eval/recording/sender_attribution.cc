#include "eval/recording/sender_attribution.h"

#include "auth/trailer.h"

namespace fleetmap::eval::recording {

const char* SenderAttribution::Attribute(const std::string& channel, const std::string& owner,
                                         Payload* p) {
  if (verifier_.enabled()) {
    auth::Opened opened;
    const auth::Verdict v = verifier_.Open(channel, p->data, p->size, owner, &opened);
    if (v != auth::Verdict::kAccepted) return auth::VerdictName(v);
    *p = {opened.data, opened.size};
    return nullptr;
  }
  // Without the key a trailer's MAC cannot be checked: its name and number are taken as
  // an identity trailer's are.
  auth::Trailer t;
  if (!auth::SplitTrailer(p->data, static_cast<size_t>(p->size), &t)) return "unnamed";
  if (!owner.empty() && t.sender != owner) return auth::VerdictName(auth::Verdict::kWrongSender);
  if (!windows_[t.sender].Accept(t.seq)) return auth::VerdictName(auth::Verdict::kReplayed);
  *p = {t.payload, static_cast<int>(t.payload_size)};
  return nullptr;
}

}  // namespace fleetmap::eval::recording
