// A fleet run recorded by lcm-logger (one log per multicast group: sensor, uplink, downlink)
// read back into the evaluation's RunRecord, so that the live system over the network is
// scored exactly like the in-process pipelines, plus what only a network run has: bytes per
// channel, and the latency from a temporary map closing on a vehicle to every vehicle holding
// the change (fleet_figures.h).
//
// Times: the simulator stamps messages with epoch + simulated time (fleetmap-sim --epoch), so
// message stamps minus the epoch are simulated seconds; latencies and rates use the logger's
// receive stamps (wall clock), since the simulator may run faster than real time.
//
// Whose word counts: a message on a channel that belongs to a process (the downlink to the
// aggregator, TEMPMAP_<id>, POSE_<id>, ... to vehicle <id>) is read only if its trailer
// (auth/trailer.h) names that process with a sequence number not seen before, and, with the
// fleet key, only if its MAC is right. Everything else on those channels (another fleet, a
// test tool, a copy of an old message, malformed bytes) is counted by reason and left out,
// so that it changes no figure (sender_attribution.h).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "auth/key.h"
#include "eval/recording/fleet_figures.h"
#include "eval/run_record.h"
#include "sim/world.h"

namespace fleetmap::eval::recording {

struct RecordedRunOptions {
  double epoch_s = 0.0;              // what fleetmap-sim added to simulated time, seconds
  double divergence_period_s = 0.1;  // keep one DIVERGENCE_ sample per vehicle per period
  double pose_period_s = 0.5;        // and one POSE_ sample
  // Simulated seconds the run covered: rates per channel are per simulated second (what a
  // fleet sends in real time, whatever the simulator's speed). 0: per wall-clock second.
  double duration_s = 0.0;
  std::string aggregator_sender = "aggregator";  // the aggregator's process name
  std::optional<auth::Key> fleet_key;            // the run's fleet key, if it had one
};

struct RecordedRun {
  eval::RunRecord run;
  FleetFigures fleet;
};

// Reads every log (any order; events are merged by receive time). The static map of `world`
// is version 0; MAP_KEYFRAME and MAP_DELTA rebuild every later version as a vehicle would.
// FailedPrecondition when the fleet's channels hold messages but none can be attributed (a
// log of processes that do not name themselves, or read with another fleet's key).
core::Result<RecordedRun> ReadRecordedRun(const std::vector<std::string>& log_paths,
                                          const sim::World& world,
                                          const RecordedRunOptions& options);

}  // namespace fleetmap::eval::recording
