#include "aggregator/node/uplink_gate.h"

#include "lcmtypes/channels.h"

namespace fleetmap::aggregator::node {

UplinkGate::UplinkGate(const AggregatorNodeOptions& options, NodeReporting report)
    : options_(options), report_(report), verifier_(options_.fleet_key) {}

std::optional<UplinkMessage> UplinkGate::Open(const std::string& channel, const void* data,
                                              int size) {
  ++report_.counters.messages;
  if (!PayloadAllowed(channel, data, size)) return std::nullopt;
  const std::optional<UplinkKind> kind = KindOf(channel);
  if (!kind) return std::nullopt;
  // TEMPMAP_<id>, CANDIDATES_FREE_<id> and CANDIDATES_HELD_<id> belong to vehicle <id>; any
  // member of the fleet may ask for maps.
  const std::string owner =
      lcmtypes::ChannelOwner(channel, options_.process_name).value_or(std::string());
  auth::Opened opened;
  const auth::Verdict verdict = verifier_.Open(channel, data, size, owner, &opened);
  if (verdict != auth::Verdict::kAccepted) {
    report_.Refuse(std::string("auth: ") + auth::VerdictName(verdict),
                   report_.counters.auth_refused,
                   channel.substr(0, 80) + ": " + auth::RefusalText(verdict));
    return std::nullopt;
  }
  return UplinkMessage{*kind, opened.data, opened.size};
}

bool UplinkGate::PayloadAllowed(const std::string& channel, const void* data, int size) {
  if (size < 0 || (size > 0 && data == nullptr)) {
    report_.Refuse("no payload", report_.counters.malformed_messages,
                   channel + ": a message without payload");
    return false;
  }
  if (size > options_.limits.max_received_bytes) {
    report_.Refuse("oversize received", report_.counters.oversize_received,
                   channel.substr(0, 80) + ": a message of " + std::to_string(size) +
                       " bytes refused (limits.max_received_bytes " +
                       std::to_string(options_.limits.max_received_bytes) + ")");
    return false;
  }
  return true;
}

std::optional<UplinkKind> UplinkGate::KindOf(const std::string& channel) {
  if (channel == lcmtypes::kTempMapAckChannel) {
    // Matches TEMPMAP_.*: our own acknowledgement, when both links share a group.
    ++report_.counters.ignored_messages;
    return std::nullopt;
  }
  if (lcmtypes::HasPrefix(channel, lcmtypes::kTempMapPrefix)) return UplinkKind::kTempMapTile;
  if (lcmtypes::HasPrefix(channel, lcmtypes::kCandidatesFreePrefix))
    return UplinkKind::kCandidatesFree;
  if (lcmtypes::HasPrefix(channel, lcmtypes::kCandidatesHeldPrefix))
    return UplinkKind::kCandidatesHeld;
  if (channel == lcmtypes::kMapRequestChannel) return UplinkKind::kMapRequest;
  report_.Refuse(
      "unknown channel", report_.counters.unknown_channel,
      "message on channel '" + channel.substr(0, 80) + "', which the aggregator does not read");
  return std::nullopt;
}

}  // namespace fleetmap::aggregator::node
