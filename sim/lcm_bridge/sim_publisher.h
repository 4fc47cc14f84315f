// Publishes the simulator's events over LCM exactly as real vehicles would report them:
// SCAN_<id> and ODOM_<id>, plus EXTPOSE_<id> for vehicles with an external localization and
// TRUTH_<id> with the ground-truth pose (for evaluation; never present on a real fleet).
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>

#include "sim/simulator.h"

namespace fleetmap::sim::lcm_bridge {

struct SimPublisherOptions {
  double epoch_s = 0.0;       // added to simulated time for the messages' utime
  bool publish_truth = true;  // TRUTH_<id>
};

struct PublishCounters {
  int64_t messages = 0;
  int64_t bytes = 0;
  int64_t failures = 0;  // publish() returned an error
};

class SimPublisher {
 public:
  // `lcm` and `world` outlive the publisher.
  SimPublisher(lcm::LCM* lcm, const sim::World* world, SimPublisherOptions options = {});

  void Publish(const sim::SimEvent& event);
  const PublishCounters& counters() const { return counters_; }

 private:
  template <typename Msg>
  void Send(const std::string& channel, const Msg& msg);

  lcm::LCM* lcm_;
  const sim::World* world_;
  const SimPublisherOptions options_;
  std::map<size_t, int32_t> scan_seq_;
  PublishCounters counters_;
};

}  // namespace fleetmap::sim::lcm_bridge
