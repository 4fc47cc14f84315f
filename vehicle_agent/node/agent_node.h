// The agent process without its sockets: the LCM and driver edge of the vehicle_agent
// library. Messages come in as (link, channel, bytes), scans and odometry from drivers as
// core types, time is passed in, and everything it sends goes through a Publisher, so that
// tests run it in memory and the process binds it to LCM (lcm_links.h).
//
// Per loop (Tick): a new map version goes to the pipeline without stopping it; queued scans
// are localized (POSE_<id>, DIVERGENCE_<id>) and closed temporary maps go to the outbox,
// which sends their tiles (TEMPMAP_<id>) until the aggregator acknowledges them; MAP_REQUEST
// when the map needs catching up; the candidates the scans saw free or held
// (CANDIDATES_FREE_<id>, CANDIDATES_HELD_<id>,
// watching MAP_CANDIDATES); STATUS_agent_<id> every status period. Bad input is
// counted, logged once per cause, and never stops the node.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "auth/signer.h"
#include "auth/verifier.h"
#include "vehicle_agent/node/agent_counters.h"
#include "vehicle_agent/node/agent_node_options.h"
#include "vehicle_agent/node/candidate_parts.h"
#include "vehicle_agent/node/node_io.h"
#include "vehicle_agent/node/sequence_store.h"
#include "vehicle_agent/node/tile_send_queue.h"

namespace fleetmap::vehicle_agent::node {

class AgentNode {
 public:
  // `publisher` outlives the node. `static_map`: the static map file, held as version 0
  // (the aggregator's version 0), or nothing: wait for a keyframe. Reloads the temporary
  // maps left pending in options.outbox.state_dir and continues their numbering.
  static core::Result<std::unique_ptr<AgentNode>> Create(
      AgentNodeOptions options, Publisher* publisher, LogSink log,
      std::optional<core::OccupancyGrid> static_map, double now_s);

  // What the edge must subscribe to for this configuration.
  std::vector<Subscription> Subscriptions() const;

  // One received message: decoded, checked and queued (or applied, for map tiles).
  void OnMessage(Link link, const std::string& channel, const void* data, int size, double now_s);
  // Inputs from drivers at the process edge (a SICK scanner, CAN odometry).
  void OnDriverScan(const core::LaserScan& scan);
  void OnDriverOdometry(const core::OdometrySample& odom);
  // The drivers' counters, reported in STATUS after the node's own.
  void SetInputCounters(NamedCounters counters) { input_counters_ = std::move(counters); }
  // What the process costs (process_usage.h), set by the loop; reported in STATUS as is.
  void SetProcessCounters(NamedCounters counters) { process_counters_ = std::move(counters); }

  // Applies a new map version, processes the queued inputs, sends what is due.
  void Tick(double now_s);
  // At exit: a temporary map being built is closed into the outbox (and its state folder),
  // its tiles are sent once, and a last STATUS goes out.
  void Shutdown(double now_s);
  // After Shutdown: resends what is due and takes a new map version in; sensor input waits.
  void Drain(double now_s);

  // "waiting_for_map", "waiting_for_pose", "building" (a temporary map) or "running".
  std::string state() const;
  int32_t map_version() const { return map_applied_ ? applied_version_ : -1; }
  const MapFollower& map() const { return follower_; }
  const AgentPipeline& pipeline() const { return pipeline_; }
  const TempMapOutbox& outbox() const { return outbox_; }
  const AgentNodeCounters& counters() const { return counters_; }
  NamedCounters AllCounters() const;
  const AgentNodeOptions& options() const { return options_; }
  // A fleet key is configured: what is sent is signed, what the downlink brings must be.
  bool authenticated() const { return verifier_.enabled(); }
  const auth::AuthCounters& auth_counters() const { return verifier_.counters(); }

 private:
  AgentNode(AgentNodeOptions options, Publisher* publisher, LogSink log, double now_s);

  // Channel handlers: decode, check, hand on.
  void OnScan(const void* data, int size);
  void OnOdometry(const void* data, int size);
  void OnExternalPose(const void* data, int size);
  void OnAck(const void* data, int size);
  void OnDelta(const void* data, int size);
  void OnKeyframe(const void* data, int size);
  void OnAggregatorStatus(const void* data, int size, double now_s);
  void OnCandidates(const void* data, int size);
  void SendSeenFree(double now_s);
  template <typename T>
  std::optional<T> Decode(const std::string& channel, const void* data, int size);
  void Malformed(const std::string& channel, const core::Status& why);
  bool OurVehicle(const std::string& channel, const std::string& vehicle_id);
  void MapTile(const std::string& channel, const core::Result<bool>& added);

  void ApplyMap();
  void Process(const SensorInput& input, double now_s);
  void ProcessScan(const core::LaserScan& scan, double now_s);
  void ProcessExternalPose(const core::PoseEstimate& pose);
  void InitializeFromExternal(const core::PoseEstimate& pose);
  void ReserveSequences(int32_t from);  // stores `from` + a block as the next number
  // At the first odometry sample: the kept pose, when the vehicle has not moved since.
  void ResumeFromKeptPose(const core::Pose2& odometry);
  // Keeps the pose of a well-localized vehicle that moved, at most once per period.
  void KeepPose(const AgentStep& step, double now_s, bool now);
  // Lost, found again and relocalized: said once per change, and in the counters.
  void ReportLocalization(const LocalizerStats& stats);
  void Keep(const core::TempMap& map, double now_s);
  // Due tiles join the send queue; as many leave as the pacer allows (all of them: at exit).
  void SendTiles(double now_s, bool all = false);
  void SendMapRequest(double now_s);
  void SendStatus(double now_s);
  void PublishStep(const core::LaserScan& scan, const AgentStep& step);
  template <typename T>
  void Send(Link link, const std::string& channel, const T& message);
  int64_t Utime(double now_s) const;

  const AgentNodeOptions options_;
  Publisher* const publisher_;
  CauseLog log_;
  int64_t answered_recovery_ = 0;  // the aggregator's last recovery this vehicle answered
  SequenceStore sequences_;
  PoseStore poses_;  // the last good pose (pose_store.h)
  // Numbers below this are on disk as used (reserved kSequenceBlock at a time).
  int32_t sequences_reserved_ = 1;
  AgentPipeline pipeline_;
  TempMapOutbox outbox_;
  MapFollower follower_;
  InputQueue queue_;
  TileSendQueue sends_;
  bool map_dirty_ = false;  // the follower has a version the pipeline does not
  bool map_applied_ = false;
  int32_t applied_version_ = -1;
  bool pose_initialized_ = false;
  // The kept pose (pose_store.h): read at start, used or not at the first odometry sample.
  std::optional<KeptPose> kept_pose_;
  std::optional<core::Pose2> odometry_;  // the last sample's pose
  std::optional<KeptPose> last_kept_;    // stored by this run
  double next_keep_s_ = 0.0;
  std::optional<AgentStep> last_step_;                // the pose kept at exit
  std::optional<core::PoseEstimate> early_external_;  // before the first map
  bool building_ = false;
  CandidateParts candidates_;
  double next_seen_free_s_ = 0.0;
  double next_status_s_;
  AgentNodeCounters counters_;
  NamedCounters input_counters_;
  NamedCounters process_counters_;
  auth::Signer signer_;
  auth::Verifier verifier_;
};

}  // namespace fleetmap::vehicle_agent::node
