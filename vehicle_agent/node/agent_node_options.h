// Every setting of the agent node, with its default and unit. The process fills them from
// its YAML file and flags (agent_config.h); docs/agent_process.md lists them in that order.
#pragma once

#include <optional>
#include <string>

#include "auth/key.h"
#include "core/codec/send_pacer.h"
#include "vehicle_agent/agent_pipeline.h"
#include "vehicle_agent/node/input_queue.h"
#include "vehicle_agent/node/map_follower.h"
#include "vehicle_agent/node/node_io.h"
#include "vehicle_agent/node/pose_store.h"
#include "vehicle_agent/tempmap_outbox.h"

namespace fleetmap::vehicle_agent::node {

// Where the vehicle's first pose on the map comes from.
enum class InitialPoseSource {
  kGiven,          // pipeline.localizer.initial_pose_in_map with its sigmas (--initial-pose)
  kGlobal,         // global localization over the map's free cells
  kFirstExternal,  // the first EXTPOSE_<id> (needs use_external_pose)
};

struct AgentNodeOptions {
  // vehicle_id (1-64 of [A-Za-z0-9_-]: it is part of channel names), scanner mount,
  // localization, divergence, temporary-map builder.
  AgentPipelineOptions pipeline;
  OutboxOptions outbox;  // outbox.state_dir: pending temporary maps survive restarts
  MapFollowerOptions map;
  InputQueueOptions queue;
  InitialPoseSource initial_pose = InitialPoseSource::kGiven;
  // The last good pose, kept in outbox.state_dir: a restart on a vehicle that has not moved
  // starts there, before the given pose or a global search (not before kFirstExternal).
  KeptPoseOptions last_pose;
  bool scans_from_lcm = true;      // SCAN_<id> on the sensor link (false: a scanner driver)
  bool odometry_from_lcm = true;   // ODOM_<id> on the sensor link (false: CAN or none)
  bool use_external_pose = false;  // EXTPOSE_<id> on the sensor link
  Link pose_link = Link::kUplink;  // where POSE_<id> and DIVERGENCE_<id> go (docs/channels.md)
  double status_period_s = 1.0;    // STATUS_agent_<id> period, s, > 0
  // Temporary-map tiles leave at most at this rate (tiles/s) after a burst: a map of tens of
  // tiles sent at once overflows slow readers (LCM queues 30 messages per subscription).
  core::PacerOptions uplink_pacer;
  // Added to the node's clock (now_s) for the utime of the messages it sends, s: the process
  // passes a monotonic clock and sets this to wall clock minus monotonic clock.
  double utime_offset_s = 0.0;
  std::string software_version = "unknown";  // in STATUS
  // The fleet key (docs/security.md): every message sent is signed as the vehicle id, and
  // downlink messages count only if signed by `aggregator_sender`. None: unauthenticated.
  std::optional<auth::Key> fleet_key;
  std::string aggregator_sender = "aggregator";  // the aggregator's process name
  core::Status Validate() const;
};

// [A-Za-z0-9_-], 1 to 64 characters: safe inside LCM channel names (which are patterns).
core::Status CheckVehicleId(const std::string& id);

}  // namespace fleetmap::vehicle_agent::node
