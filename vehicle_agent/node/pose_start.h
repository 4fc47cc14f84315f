// Where the filter's first pose comes from, and the pose kept for the next start. The first
// map starts the filter at the given pose or with a global search (AgentNodeOptions::
// initial_pose), unless
//   - a pose kept by an earlier run (pose_store.h) waits for the first odometry sample, which
//     tells whether the vehicle has moved since: if not, the filter starts there;
//   - the first external pose is to start it (kFirstExternal); one that came before the first
//     map is held until then.
// While the node runs, the pose of a well-localized vehicle that moved is kept, at most once
// per last_pose.period_s, and at exit.
#pragma once

#include <optional>

#include "vehicle_agent/agent_pipeline.h"
#include "vehicle_agent/node/agent_counters.h"
#include "vehicle_agent/node/agent_node_options.h"
#include "vehicle_agent/node/message_checks.h"
#include "vehicle_agent/node/node_io.h"
#include "vehicle_agent/node/pose_store.h"

namespace fleetmap::vehicle_agent::node {

class PoseStart {
 public:
  // `pipeline`, `log`, `checks` and `counters` (starts_from_last_pose) outlive it. Poses are
  // kept in options.outbox.state_dir.
  PoseStart(const AgentNodeOptions& options, AgentPipeline* pipeline, CauseLog* log,
            MessageChecks* checks, AgentNodeCounters* counters);

  // At start: reads the kept pose, when poses are kept and the first pose is not the first
  // external one. A kept pose that cannot be read is logged and not used.
  void LoadKept();
  // The first map is in use.
  void OnFirstMap();
  // Every valid odometry sample (its pose in the odometry frame).
  void OnOdometry(const core::Pose2& odometry);
  // Every external pose: held before the first map, the first pose under kFirstExternal, and
  // handed to the pipeline after that (which counts what it refuses).
  void OnExternalPose(const core::PoseEstimate& pose);
  // Every localized scan's step.
  void OnStep(const AgentStep& step, double now_s);
  // At exit: the last step's pose is kept now, whatever the period.
  void KeepLast(double now_s);

  // The filter has its first pose: scans may be localized.
  bool initialized() const { return initialized_; }
  const PoseStore& store() const { return poses_; }

 private:
  void InitializeFromExternal(const core::PoseEstimate& pose);
  void ResumeFromKeptPose(const core::Pose2& odometry);
  void KeepPose(const AgentStep& step, double now_s, bool now);

  const AgentNodeOptions& options_;
  AgentPipeline* const pipeline_;
  CauseLog* const log_;
  MessageChecks* const checks_;
  AgentNodeCounters* const counters_;
  PoseStore poses_;
  bool map_in_use_ = false;
  bool initialized_ = false;
  // The kept pose: read at start, used or not at the first odometry sample.
  std::optional<KeptPose> kept_pose_;
  std::optional<core::Pose2> odometry_;  // the last sample's pose
  std::optional<KeptPose> last_kept_;    // stored by this run
  double next_keep_s_ = 0.0;
  std::optional<AgentStep> last_step_;                // the pose kept at exit
  std::optional<core::PoseEstimate> early_external_;  // before the first map
};

}  // namespace fleetmap::vehicle_agent::node
