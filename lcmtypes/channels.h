// The names of fleetmap's LCM channels (docs/channels.md), built and taken apart only here:
// a process that matches a channel by a literal of its own would miss a renamed channel
// silently.
#pragma once

#include <optional>
#include <string>

namespace fleetmap::lcmtypes {

// Sensor group: on one vehicle, its scanner and odometry (or the simulator) to its agent.
constexpr char kScanPrefix[] = "SCAN_";
constexpr char kOdomPrefix[] = "ODOM_";
// A pose from a vehicle's own (external) localization system.
constexpr char kExternalPosePrefix[] = "EXTPOSE_";
// The simulator's ground-truth pose of a vehicle (never on a real fleet).
constexpr char kTruthPrefix[] = "TRUTH_";
// Uplink: what a vehicle's agent publishes.
constexpr char kPosePrefix[] = "POSE_";
constexpr char kDivergencePrefix[] = "DIVERGENCE_";
constexpr char kTempMapPrefix[] = "TEMPMAP_";
constexpr char kTempMapChannelRegex[] = "TEMPMAP_.*";
constexpr char kMapRequestChannel[] = "MAP_REQUEST";
// The fleet map's candidates a vehicle's scans passed through, none ending there.
constexpr char kCandidatesFreePrefix[] = "CANDIDATES_FREE_";
constexpr char kCandidatesFreeChannelRegex[] = "CANDIDATES_FREE_.*";
// ... and those its beams kept ending at for long enough: something that stays.
constexpr char kCandidatesHeldPrefix[] = "CANDIDATES_HELD_";
constexpr char kCandidatesHeldChannelRegex[] = "CANDIDATES_HELD_.*";
// Downlink: what the aggregator publishes. TEMPMAP_ACK shares the prefix of the vehicles'
// TEMPMAP_<id> (and so matches kTempMapChannelRegex): IsTempMapTileChannel tells them apart.
constexpr char kTempMapAckChannel[] = "TEMPMAP_ACK";
constexpr char kMapDeltaChannel[] = "MAP_DELTA";
constexpr char kMapKeyframeChannel[] = "MAP_KEYFRAME";
constexpr char kMergeReportChannel[] = "MERGE_REPORT";
// The current map's candidates (cells seen occupied once), for the vehicles to watch.
constexpr char kMapCandidatesChannel[] = "MAP_CANDIDATES";
// Cells per MAP_CANDIDATES or CANDIDATES_FREE_<id> message: 1.2 KB, one UDP datagram.
constexpr int kMaxCandidateCellsPerMessage = 300;
// Cells per CANDIDATES_HELD_<id> message (a cell and two times each): 1.2 KB.
constexpr int kMaxHeldCellsPerMessage = 100;
// Both: every process's heartbeat, STATUS_<process>: STATUS_agent_<id>, STATUS_aggregator.
constexpr char kStatusPrefix[] = "STATUS_";
constexpr char kAgentStatusPrefix[] = "STATUS_agent_";
// Counters of STATUS_aggregator that ask the vehicles for something: after an operator's
// `fleetmap-mapctl recover`, the recovery's id and the version it kept; each vehicle sends
// the merged maps it holds from later versions again, once per id (docs/operations.md).
constexpr char kRecoveryIdCounter[] = "recovery_id";
constexpr char kRecoveredVersionCounter[] = "recovered_version";

inline std::string ScanChannel(const std::string& vehicle) { return kScanPrefix + vehicle; }
inline std::string OdomChannel(const std::string& vehicle) { return kOdomPrefix + vehicle; }
inline std::string ExternalPoseChannel(const std::string& vehicle) {
  return kExternalPosePrefix + vehicle;
}
inline std::string TruthChannel(const std::string& vehicle) { return kTruthPrefix + vehicle; }
inline std::string PoseChannel(const std::string& vehicle) { return kPosePrefix + vehicle; }
inline std::string DivergenceChannel(const std::string& vehicle) {
  return kDivergencePrefix + vehicle;
}
inline std::string TempMapChannel(const std::string& vehicle) { return kTempMapPrefix + vehicle; }
inline std::string CandidatesFreeChannel(const std::string& vehicle) {
  return kCandidatesFreePrefix + vehicle;
}
inline std::string CandidatesHeldChannel(const std::string& vehicle) {
  return kCandidatesHeldPrefix + vehicle;
}
inline std::string StatusChannel(const std::string& process) { return kStatusPrefix + process; }

inline bool HasPrefix(const std::string& channel, const char* prefix) {
  return channel.rfind(prefix, 0) == 0;
}
// What follows the prefix: ChannelSuffix("TEMPMAP_v1", kTempMapPrefix) is "v1"; "" when the
// channel does not start with the prefix.
inline std::string ChannelSuffix(const std::string& channel, const char* prefix) {
  return HasPrefix(channel, prefix) ? channel.substr(std::char_traits<char>::length(prefix)) : "";
}
// TEMPMAP_<id>, a vehicle's temporary-map tile; not the aggregator's TEMPMAP_ACK.
inline bool IsTempMapTileChannel(const std::string& channel) {
  return HasPrefix(channel, kTempMapPrefix) && channel != kTempMapAckChannel;
}

// Who may send on `channel` (docs/security.md): the downlink and STATUS_<aggregator> belong
// to the aggregator's process name, a vehicle's channels (TEMPMAP_<id>, POSE_<id>,
// DIVERGENCE_<id>, CANDIDATES_*_<id>, STATUS_agent_<id>) to vehicle <id>, MAP_REQUEST to any
// member of the fleet (""); none for channels no fleet process sends (the sensor group).
inline std::optional<std::string> ChannelOwner(const std::string& channel,
                                               const std::string& aggregator) {
  if (channel == kTempMapAckChannel || channel == kMapDeltaChannel ||
      channel == kMapKeyframeChannel || channel == kMergeReportChannel ||
      channel == kMapCandidatesChannel || channel == StatusChannel(aggregator))
    return aggregator;
  if (channel == kMapRequestChannel) return std::string();
  for (const char* prefix : {kAgentStatusPrefix, kPosePrefix, kDivergencePrefix,
                             kCandidatesFreePrefix, kCandidatesHeldPrefix, kTempMapPrefix}) {
    if (HasPrefix(channel, prefix)) return ChannelSuffix(channel, prefix);
  }
  return std::nullopt;
}

}  // namespace fleetmap::lcmtypes
