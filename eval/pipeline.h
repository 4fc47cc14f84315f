// A pipeline turns the simulator's sensor events into a RunRecord. The evaluation runs every
// pipeline the same way, in-process and deterministic: the oracle now, the vehicle agents and
// the aggregator once they exist.
#pragma once

#include <memory>
#include <string>

#include "eval/run_record.h"
#include "sim/simulator.h"

namespace fleetmap::eval {

class Pipeline {
 public:
  virtual ~Pipeline() = default;
  virtual std::string name() const = 0;
  // Every sensor event, in time order.
  virtual void OnEvent(const sim::SimEvent& event) = 0;
  // After the last event: what the run produced.
  virtual RunRecord Finish(const sim::Simulator& simulator) = 0;
};

// The oracle merges exactly what the scanners saw of every change, placed where it truly is:
// it scores F1 = 1 and no errors, which proves the evaluation, and is the reference the real
// pipeline is compared with.
std::unique_ptr<Pipeline> MakeOraclePipeline();

// Runs the world's scenario through `pipeline`; `progress` (may be null) is called about
// every simulated 10 s with the simulated time.
RunRecord RunScenario(const sim::World& world, Pipeline& pipeline, sim::Simulator& simulator,
                      void (*progress)(double t_s) = nullptr);

}  // namespace fleetmap::eval
