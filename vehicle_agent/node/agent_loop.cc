#include "vehicle_agent/node/agent_loop.h"

#include <algorithm>

#include "vehicle_agent/node/process_usage.h"

namespace fleetmap::vehicle_agent::node {
namespace {

// With CAN odometry the loop passes more often: samples reach the node within 10 ms.
constexpr double kCanWaitS = 0.01;
// A scanner's client waits on its own socket: the LCM links are looked at between scans.
constexpr double kScannerWaitS = 0.02;
// How often the process's CPU time and memory are read for STATUS (a /proc read each time).
constexpr double kUsagePeriodS = 1.0;
// Once the outbox is empty at shutdown, the delta of the last merge follows its
// acknowledgement within milliseconds on a LAN; this much more is taken in.
constexpr double kDrainSettleS = 0.3;

NamedCounters InputCounters(const LoopSources& sources) {
  NamedCounters out;
  if (sources.scanner) {
    const NamedCounters s = sources.scanner->Counters();
    out.insert(out.end(), s.begin(), s.end());
  }
  if (sources.odometry) {
    const NamedCounters c = sources.odometry->Counters();
    out.insert(out.end(), c.begin(), c.end());
  }
  return out;
}

}  // namespace

core::Status RunAgentLoop(AgentNode& node, const LoopSources& sources, const LoopOptions& options,
                          const volatile std::sig_atomic_t* stop,
                          const std::function<double()>& clock) {
  const double start_s = clock();
  double usage_read_s = start_s - kUsagePeriodS;
  core::Status failure;
  while (!*stop) {
    if (options.duration_s > 0.0 && clock() - start_s >= options.duration_s) break;
    double lcm_wait_s = options.wait_s;
    if (sources.odometry) lcm_wait_s = std::min(lcm_wait_s, kCanWaitS);
    if (sources.scanner) lcm_wait_s = 0.0;
    const core::Result<int> handled = sources.links->Handle(lcm_wait_s);
    if (!handled.ok()) {
      failure = handled.status();
      break;
    }
    if (sources.scanner) {
      if (std::optional<DriverScan> scan =
              sources.scanner->Next(std::min(options.wait_s, kScannerWaitS)))
        node.OnDriverScan(scan->scan);
    }
    if (sources.odometry) {
      for (const core::OdometrySample& odom : sources.odometry->Drain())
        node.OnDriverOdometry(odom);
    }
    if (sources.scanner || sources.odometry) node.SetInputCounters(InputCounters(sources));
    const double now_s = clock();
    if (now_s - usage_read_s >= kUsagePeriodS) {
      node.SetProcessCounters(ProcessUsageCounters());
      usage_read_s = now_s;
    }
    node.Tick(now_s);
  }
  node.Shutdown(clock());
  if (failure.ok()) failure = DrainAtShutdown(node, *sources.links, options, clock);
  return failure;
}

core::Status DrainAtShutdown(AgentNode& node, AgentLinks& links, const LoopOptions& options,
                             const std::function<double()>& clock) {
  const double end_s = clock() + options.shutdown_drain_s;
  double empty_since_s = -1.0;
  for (double now_s = clock(); now_s < end_s; now_s = clock()) {
    const core::Result<int> handled = links.Handle(std::min(options.wait_s, end_s - now_s));
    if (!handled.ok()) return handled.status();
    now_s = clock();
    node.Drain(now_s);
    if (node.outbox().pending() > 0) {
      empty_since_s = -1.0;
    } else if (empty_since_s < 0.0) {
      empty_since_s = now_s;
    } else if (now_s - empty_since_s >= kDrainSettleS) {
      break;
    }
  }
  return core::OkStatus();
}

}  // namespace fleetmap::vehicle_agent::node
