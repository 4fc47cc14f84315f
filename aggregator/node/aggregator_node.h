// The aggregator process without its sockets: the LCM edge of the aggregator library.
// Messages come in as (channel, bytes, time), everything it sends goes through a Publisher,
// and time is passed in, so tests run it in memory and a replay runs it from a log.
//
// Uplink, what it reads:
//   TEMPMAP_<vehicle>  temporary-map tiles. The tile must name the channel's vehicle. Tiles
//       are assembled (core::TempMapAssembler); incomplete maps get PENDING acknowledgements
//       (ack_schedule.h) listing the tiles received, kept on disk first (tile_spool.h). A
//       complete map goes to Aggregator::Submit with the completing tile's own time (utime),
//       never the clock, so a replay merges exactly as the live run did; then TEMPMAP_ACK
//       MERGED (after the journal write) or REJECTED, MERGE_REPORT, and MAP_DELTA tiles of
//       the new version. A failed journal write (a full disk) acknowledges nothing: the
//       vehicle resends and the merge is tried again. A map already merged or rejected is
//       answered DUPLICATE and never merged twice, also after a restart.
//   MAP_REQUEST  the deltas since the vehicle's version when all are retained, otherwise
//       keyframe tiles (all, or the tiles listed), coalesced (keyframe_schedule.h).
//   CANDIDATES_FREE_<vehicle>  candidates the vehicle's scans saw empty: dropped
//       (Aggregator::DropCandidatesSeenFree, a version of its own and its MAP_DELTA).
//   CANDIDATES_HELD_<vehicle>  candidates the vehicle's beams kept ending at for long enough:
//       added (Aggregator::ConfirmCandidatesHeld, likewise).
// Downlink, what it sends: TEMPMAP_ACK, MERGE_REPORT, MAP_DELTA, MAP_KEYFRAME (asked tiles
// and a rolling keyframe, one round per keyframe_period_s, while the downlink has room),
// MAP_CANDIDATES (after each change of the candidates, and every keyframe_period_s),
// STATUS_<process_name> every status_period_s.
// Bad input of any kind is counted by cause (node_counters.h), logged once per cause, and
// changes nothing.
//
// Built from parts, each owning one job, wired here: uplink_gate.h (which messages get in),
// temp_map_receiver.h (tiles into complete maps), map_committer.h (complete maps into the
// current map, and the acknowledgement that earns), candidate_reports.h (the vehicles'
// candidate reports), map_request_answerer.h (MAP_REQUEST, the rolling keyframe) and
// map_publisher.h (everything sent).
#pragma once

#include <map>
#include <memory>
#include <string>

#include "aggregator/aggregator.h"
#include "aggregator/node/candidate_reports.h"
#include "aggregator/node/map_committer.h"
#include "aggregator/node/map_publisher.h"
#include "aggregator/node/map_request_answerer.h"
#include "aggregator/node/node_counters.h"
#include "aggregator/node/node_io.h"
#include "aggregator/node/node_options.h"
#include "aggregator/node/temp_map_receiver.h"
#include "aggregator/node/tile_spool.h"
#include "aggregator/node/uplink_gate.h"
#include "aggregator/node/vehicle_limits.h"
#include "auth/verifier.h"

namespace fleetmap::aggregator::node {

class AggregatorNode {
 public:
  // `publisher` outlives the node; nullptr sends nothing (a replay). Remembers every merge
  // of the aggregator's history and reloads the tiles an earlier run kept in
  // options.spool_dir. Fails on invalid options or an unusable spool folder.
  static core::Result<std::unique_ptr<AggregatorNode>> Create(Aggregator aggregator,
                                                              AggregatorNodeOptions options,
                                                              Publisher* publisher, LogSink log,
                                                              double now_s);

  // One message received on the uplink; `now_s` is the receive time, seconds.
  void OnMessage(const std::string& channel, const void* data, int size, double now_s);
  // Timers: PENDING acknowledgements, answers to MAP_REQUEST, the rolling keyframe, STATUS,
  // dropping incomplete maps that went silent. Call it often (every 100 ms or so), and within
  // milliseconds while sending() says asked keyframe tiles wait.
  void Tick(double now_s);
  bool sending() const { return answerer_.sending(); }
  // Writes a snapshot of the current map (FailedPrecondition without a state folder).
  core::Status Snapshot() { return aggregator_.WriteSnapshot(); }

  // "running", or "persist_failed" after a journal write failed until one succeeds.
  std::string state() const { return committer_.persist_failed() ? "persist_failed" : "running"; }
  const Aggregator& aggregator() const { return aggregator_; }
  const NodeCounters& counters() const { return counters_; }
  // The largest message sent so far on each channel, bytes.
  const std::map<std::string, size_t>& largest_messages() const {
    return publisher_.largest_messages();
  }
  size_t incomplete_maps() const { return receiver_.incomplete_maps(); }
  // A fleet key is configured: what is sent is signed, what is received must be.
  bool authenticated() const { return gate_.verifier().enabled(); }
  const auth::AuthCounters& auth_counters() const { return gate_.verifier().counters(); }
  int throttled_vehicles() const { return limits_.throttled_vehicles(); }
  // The line the process ends with (map_hash.h).
  std::string FinalLine() const;

 private:
  AggregatorNode(Aggregator aggregator, AggregatorNodeOptions options, TileSpool spool,
                 Publisher* publisher, LogSink log, double now_s);
  void SendStatus(double now_s);

  // Shared by the parts, declared before them: they hold references.
  const AggregatorNodeOptions options_;
  Aggregator aggregator_;  // changed by the committer and the candidate reports only
  NodeCounters counters_;
  CauseLog log_;
  TileSpool spool_;       // filled by the receiver, emptied by the committer
  VehicleLimits limits_;  // tile rate (receiver) and merge rate (committer) of each vehicle

  UplinkGate gate_;
  MapPublisher publisher_;
  MapCommitter committer_;
  CandidateReports candidate_reports_;
  MapRequestAnswerer answerer_;
  TempMapReceiver receiver_;
  double next_status_s_;
};

}  // namespace fleetmap::aggregator::node
