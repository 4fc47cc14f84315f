// The agent process without its sockets: the LCM and driver edge of the vehicle_agent
// library. Messages come in as (link, channel, bytes), scans and odometry from drivers as
// core types, time is passed in, and everything it sends goes through a Publisher, so that
// tests run it in memory and the process binds it to LCM (agent_links.h).
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
#include "vehicle_agent/node/agent_sender.h"
#include "vehicle_agent/node/candidate_parts.h"
#include "vehicle_agent/node/map_updates.h"
#include "vehicle_agent/node/message_checks.h"
#include "vehicle_agent/node/node_io.h"
#include "vehicle_agent/node/pose_start.h"
#include "vehicle_agent/node/sensor_intake.h"
#include "vehicle_agent/node/sequence_store.h"
#include "vehicle_agent/node/tempmap_uplink.h"
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
  // Its parts hold pointers to its log and counters: it stays where it was made.
  AgentNode(const AgentNode&) = delete;
  AgentNode& operator=(const AgentNode&) = delete;

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
  int32_t map_version() const { return maps_.version_in_use(); }
  const MapFollower& map() const { return maps_.follower(); }
  const AgentPipeline& pipeline() const { return pipeline_; }
  const TempMapOutbox& outbox() const { return uplink_.outbox(); }
  const AgentNodeCounters& counters() const { return counters_; }
  NamedCounters AllCounters() const;
  const AgentNodeOptions& options() const { return options_; }
  // A fleet key is configured: what is sent is signed, what the downlink brings must be.
  bool authenticated() const { return verifier_.enabled(); }
  const auth::AuthCounters& auth_counters() const { return verifier_.counters(); }

 private:
  AgentNode(AgentNodeOptions options, Publisher* publisher, LogSink log, double now_s);

  // Downlink handlers: decode, check, hand on.
  void OnAck(const void* data, int size);
  void OnDelta(const void* data, int size);
  void OnKeyframe(const void* data, int size);
  void OnAggregatorStatus(const void* data, int size, double now_s);
  void OnCandidates(const void* data, int size);

  // A completed map version goes to the pipeline; the first one starts the filter (PoseStart).
  void ApplyMap();
  void Process(const SensorInput& input, double now_s);
  void ProcessScan(const core::LaserScan& scan, double now_s);
  // Lost, found again and relocalized: said once per change, and in the counters.
  void ReportLocalization(const LocalizerStats& stats);
  // Due tiles join the send queue; as many leave as the pacer allows (all of them: at exit).
  void SendTiles(double now_s, bool all = false);
  void SendCandidates(double now_s);
  void SendStatus(double now_s);

  // The parts below hold pointers to log_ and counters_, which are declared first.
  const AgentNodeOptions options_;
  CauseLog log_;
  AgentNodeCounters counters_;
  MessageChecks checks_;
  AgentSender sender_;
  AgentPipeline pipeline_;
  TempMapUplink uplink_;
  MapUpdates maps_;
  PoseStart pose_;  // the filter's first pose, and the pose kept for the next start
  SensorIntake intake_;
  bool building_ = false;
  CandidateParts candidates_;
  double next_candidates_s_ = 0.0;
  double next_status_s_;
  NamedCounters input_counters_;
  NamedCounters process_counters_;
  auth::Verifier verifier_;
};

}  // namespace fleetmap::vehicle_agent::node
