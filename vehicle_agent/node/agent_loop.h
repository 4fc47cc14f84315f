// The agent's single-threaded event loop: waits on the LCM links (or on the scanner, whose
// client waits on its socket), hands everything received to the node, drains CAN odometry,
// and ticks the node. It stops when the stop flag is set (SIGINT/SIGTERM) or after the
// configured duration, and then shuts the node down (a map being built goes to the outbox)
// and drains it: acknowledgements and map versions are taken in until the outbox is empty
// (and a little longer, for the version the last merge made) or shutdown_drain_s is over.
#pragma once

#include <csignal>
#include <functional>

#include "vehicle_agent/node/agent_links.h"
#include "vehicle_agent/node/agent_node.h"
#include "vehicle_agent/node/can_odometry_input.h"
#include "vehicle_agent/node/sick_scan_input.h"

namespace fleetmap::vehicle_agent::node {

struct LoopSources {
  AgentLinks* links = nullptr;           // required
  SickScanInput* scanner = nullptr;      // scan_source sick
  CanOdometryInput* odometry = nullptr;  // odom_source can
};

struct LoopOptions {
  double wait_s = 0.05;     // longest wait for input per pass, s, > 0
  double duration_s = 0.0;  // stop after this long, s; 0: only on the stop flag
  // After the stop, how long the maps sent at shutdown may take to be acknowledged, s, >= 0:
  // the vehicle then need not resend them after its restart, and the map it holds at exit
  // has their change. 0: leave at once.
  double shutdown_drain_s = 2.0;
};

// Runs until `*stop` becomes non-zero or the duration is over; `clock` is monotonic, in
// seconds (the node's now_s). Returns an error when an LCM link failed (the node is shut
// down all the same).
core::Status RunAgentLoop(AgentNode& node, const LoopSources& sources, const LoopOptions& options,
                          const volatile std::sig_atomic_t* stop,
                          const std::function<double()>& clock);
// The drain after Shutdown (RunAgentLoop calls it): LCM only, no sensor input is processed.
core::Status DrainAtShutdown(AgentNode& node, AgentLinks& links, const LoopOptions& options,
                             const std::function<double()>& clock);

}  // namespace fleetmap::vehicle_agent::node
