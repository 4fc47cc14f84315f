// The aggregator node's downlink: everything the node sends goes out here. Each message is
// signed with the fleet key (auth/signer.h), so that vehicles can tell the aggregator from a
// forger; its size is checked against max_message_bytes, because one lost UDP packet loses a
// whole message; and the largest per channel is kept for the run's closing figures. Without a
// Publisher (a replay) nothing is encoded or sent and the counters of sent messages stay as
// they are, so a replay's counters tell what was received and merged, not what was sent.
// Reads the current map (keyframes, candidates, the version an acknowledgement names);
// changes nothing in it. Owns the signer and the largest sizes.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "aggregator/aggregator.h"
#include "aggregator/node/map_key.h"
#include "aggregator/node/messages.h"
#include "aggregator/node/node_io.h"
#include "aggregator/node/node_options.h"
#include "aggregator/node/node_reporting.h"
#include "auth/signer.h"

namespace fleetmap::aggregator::node {

class MapPublisher {
 public:
  // `aggregator` and `publisher` outlive this; `publisher` nullptr sends nothing.
  MapPublisher(const Aggregator& aggregator, const AggregatorNodeOptions& options,
               Publisher* publisher, NodeReporting report);
  MapPublisher(const MapPublisher&) = delete;
  MapPublisher& operator=(const MapPublisher&) = delete;

  // False without a Publisher: work whose only use is a message can be skipped.
  bool enabled() const { return publisher_ != nullptr; }
  // Bytes the downlink can take now without queueing them behind others (Publisher::
  // RoomBytes): traffic that can wait (keyframe tiles) goes only while there is room.
  size_t room_bytes() const;

  // TEMPMAP_ACK PENDING of an incomplete map: the tiles `received` (ascending), which the
  // vehicle will not send again, and the current map's version.
  void SendPendingAck(const MapKey& key, int32_t tile_count, std::vector<int32_t> received,
                      double now_s);
  // TEMPMAP_ACK MERGED, REJECTED (with its reason) or DUPLICATE, naming every tile. The
  // count is clamped to assembler.max_tiles: a resend of a finished map has passed no check.
  void SendFinalAck(const MapKey& key, int32_t tile_count, int8_t outcome,
                    const std::string& reason, uint64_t version, double now_s);
  // MERGE_REPORT, stamped with the map's own time `map_s`, at most max_report_matches lines.
  void SendMergeReport(const MergeReport& report, const core::Pose2& anchor_in_map, double map_s);
  // MAP_DELTA tiles of one version.
  void SendDelta(const MapDelta& delta, double now_s);
  // MAP_KEYFRAME tiles of the current map: every tile, or only the linear tile indices `only`.
  // Returns the bytes sent.
  size_t SendKeyframe(const std::vector<int32_t>* only, double now_s);
  // MAP_CANDIDATES, the whole set at the current version.
  void SendCandidates(double now_s);
  // STATUS_<process_name>.
  void SendStatus(const StatusFields& fields, double now_s);

  // The largest message sent so far on each channel, bytes.
  const std::map<std::string, size_t>& largest_messages() const { return largest_; }

 private:
  // Returns the message's bytes (0 without a Publisher).
  template <typename T>
  size_t Send(Link link, const std::string& channel, const T& message);

  const Aggregator& aggregator_;
  const AggregatorNodeOptions options_;
  Publisher* const publisher_;
  NodeReporting report_;
  auth::Signer signer_;
  std::map<std::string, size_t> largest_;
};

}  // namespace fleetmap::aggregator::node
