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
//   MAP_REQUEST  the deltas since the vehicle's version when all are retained, otherwise a
//       keyframe (whole, or the tiles listed), coalesced (request_queue.h).
//   CANDIDATES_FREE_<vehicle>  candidates the vehicle's scans saw empty: dropped
//       (Aggregator::DropCandidatesSeenFree, a version of its own and its MAP_DELTA).
//   CANDIDATES_HELD_<vehicle>  candidates the vehicle's beams kept ending at for long enough:
//       added (Aggregator::ConfirmCandidatesHeld, likewise).
// Downlink, what it sends: TEMPMAP_ACK, MERGE_REPORT, MAP_DELTA, MAP_KEYFRAME (also every
// keyframe_period_s), MAP_CANDIDATES (after each change of the candidates, and with each
// periodic keyframe), STATUS_<process_name> every status_period_s.
// Bad input of any kind is counted by cause (node_counters.h), logged once per cause, and
// changes nothing.
#pragma once

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aggregator/aggregator.h"
#include "aggregator/node/ack_schedule.h"
#include "aggregator/node/handled_maps.h"
#include "aggregator/node/held_maps.h"
#include "aggregator/node/node_counters.h"
#include "aggregator/node/node_io.h"
#include "aggregator/node/node_options.h"
#include "aggregator/node/request_queue.h"
#include "aggregator/node/tile_spool.h"
#include "aggregator/node/vehicle_limits.h"
#include "auth/signer.h"
#include "auth/verifier.h"
#include "core/temp_map_tiles.h"
#include "fleetmap/tempmap_tile_t.hpp"

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
  // Timers: PENDING acknowledgements, answers to MAP_REQUEST, the periodic keyframe, STATUS,
  // dropping incomplete maps that went silent. Call it often (every 100 ms or so).
  void Tick(double now_s);
  // Writes a snapshot of the current map (FailedPrecondition without a state folder).
  core::Status Snapshot() { return aggregator_.WriteSnapshot(); }

  // "running", or "persist_failed" after a journal write failed until one succeeds.
  std::string state() const { return persist_failed_ ? "persist_failed" : "running"; }
  const Aggregator& aggregator() const { return aggregator_; }
  const NodeCounters& counters() const { return counters_; }
  // The largest message sent so far on each channel, bytes.
  const std::map<std::string, size_t>& largest_messages() const { return largest_; }
  size_t incomplete_maps() const { return incoming_.size(); }
  // A fleet key is configured: what is sent is signed, what is received must be.
  bool authenticated() const { return verifier_.enabled(); }
  const auth::AuthCounters& auth_counters() const { return verifier_.counters(); }
  int throttled_vehicles() const { return limits_.throttled_vehicles(); }
  // The line the process ends with (map_hash.h).
  std::string FinalLine() const;

 private:
  struct Incoming {
    int32_t tile_count = 0;
    std::map<int32_t, std::vector<uint8_t>> unspooled;  // received, not yet on disk
  };
  struct Retry {
    core::TempMap map;
    int32_t tile_count = 0;
  };

  AggregatorNode(Aggregator aggregator, AggregatorNodeOptions options, Publisher* publisher,
                 LogSink log, double now_s);
  void RestoreSpool(double now_s);

  void OnTile(const std::string& channel, const void* data, int size, double now_s);
  void AddTile(const fleetmap::tempmap_tile_t& msg, const core::TempMapTile& tile,
               const std::vector<uint8_t>& bytes, bool from_spool, double now_s);
  // A complete map: merged, or held behind its vehicle's earlier ones or over its merge rate.
  void Complete(const MapKey& key, const core::TempMap& map, int32_t tile_count, double map_s,
                double now_s);
  void Merge(const MapKey& key, const core::TempMap& map, int32_t tile_count, double map_s,
             double now_s);
  // False when the journal write failed (nothing changed, nothing acknowledged).
  bool TryMerge(const MapKey& key, const core::TempMap& map, int32_t tile_count, double map_s,
                double now_s);
  void ReleaseHeld(double now_s);
  // Maps whose journal write failed wait, with every map completed after them, in arrival
  // order (a replay of the uplink merges them in that order too), and are merged when the
  // journal writes again: tried every kPersistRetryS and at each resend of one of them.
  bool Unpersisted(const MapKey& key) const;
  void KeepUnpersisted(HeldMap map, double now_s);
  void RetryUnpersisted(double now_s);
  static constexpr double kPersistRetryS = 1.0;
  void OnRequest(const void* data, int size);
  // A vehicle's CANDIDATES_FREE_<id>: the candidates it saw empty are dropped (a new version),
  // and the new set goes out.
  void OnSeenFree(const std::string& channel, const void* data, int size, double now_s);
  // A vehicle's CANDIDATES_HELD_<id>: the candidates it saw held long enough are added.
  void OnHeld(const std::string& channel, const void* data, int size, double now_s);
  // Decoded, from the vehicle whose channel it came on; refused (counted, logged) otherwise.
  template <typename Message>
  std::optional<Message> VehicleReport(const std::string& channel, const void* data, int size,
                                       const char* prefix, const std::string& name);
  void ReportApplied(const std::string& vehicle, const core::Result<std::vector<int64_t>>& cells,
                     int64_t& counter, const std::string& what, double now_s);
  void Refuse(const std::string& cause, int64_t& counter, const std::string& line);
  bool Throttled(const std::string& vehicle, double now_s);
  int PendingMaps(const std::string& vehicle) const;

  void SendPending(const MapKey& key, double now_s);
  void SendFinal(const MapKey& key, int32_t tile_count, int8_t outcome, const std::string& reason,
                 uint64_t version, double now_s);
  void SendRequested(double now_s);
  void SendKeyframe(const std::vector<int32_t>* only, double now_s);
  void SendDelta(const MapDelta& delta, double now_s);
  void SendCandidates(double now_s);
  void SendStatus(double now_s);
  void DropStale(double now_s);
  template <typename T>
  void Send(Link link, const std::string& channel, const T& message);

  Aggregator aggregator_;
  const AggregatorNodeOptions options_;
  Publisher* const publisher_;
  CauseLog log_;
  core::TempMapAssembler assembler_;
  HandledMaps handled_;
  AckSchedule acks_;
  TileSpool spool_;
  RequestQueue requests_;
  std::map<MapKey, Incoming> incoming_;  // maps being assembled
  std::map<MapKey, Retry> retry_;        // complete, over the rate with no room to hold it
  std::deque<HeldMap> unpersisted_;      // complete, waiting for the journal (arrival order)
  double next_persist_try_s_ = 0.0;
  bool persist_failed_ = false;
  double next_status_s_;
  double next_keyframe_s_;
  NodeCounters counters_;
  std::map<std::string, size_t> largest_;
  auth::Signer signer_;
  auth::Verifier verifier_;
  VehicleLimits limits_;
  HeldMaps held_;  // complete, over the vehicle's merge rate
};

}  // namespace fleetmap::aggregator::node
