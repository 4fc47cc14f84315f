// For tests that run fleetmap-agent as a process: the simulator's odometry and scans of
// vehicle "v1" published as ODOM_v1 / SCAN_v1 on a real LCM link, paced in real time.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <thread>

#include "lcmtypes/convert.h"
#include "sim/simulator.h"

namespace fleetmap::vehicle_agent::node::testing {

// Publishes the whole run of `world` at `speed` times real time, stamped from epoch_s on;
// `after_each` runs after every event (to handle what came back). Returns the true pose of
// every scan by its utime.
inline std::map<int64_t, core::Pose2> PublishSensors(lcm::LCM& sensor, const sim::World& world,
                                                     double speed,
                                                     const std::function<void()>& after_each,
                                                     double epoch_s = 1.7e9) {
  std::map<int64_t, core::Pose2> truth;
  sim::Simulator simulator(&world);
  const auto wall_start = std::chrono::steady_clock::now();
  int32_t seq = 0;
  while (auto e = simulator.Next()) {
    const double t = sim::EventTime(*e);
    std::this_thread::sleep_until(wall_start + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                   std::chrono::duration<double>(t / speed)));
    if (const auto* o = std::get_if<sim::OdometryEvent>(&*e)) {
      const core::OdometrySample odom{o->stamp_s + epoch_s, o->odom_pose, o->v_mps, o->omega_radps};
      const auto m = lcmtypes::ToMessage(odom, "v1");
      sensor.publish("ODOM_v1", &m);
    } else if (const auto* s = std::get_if<sim::ScanEvent>(&*e)) {
      core::LaserScan scan = s->scan;
      scan.stamp_s += epoch_s;
      truth[lcmtypes::ToUtime(scan.stamp_s)] = s->true_base_pose;
      const auto m = lcmtypes::ToMessage(scan, "v1", seq++);
      sensor.publish("SCAN_v1", &m);
    }
    if (after_each) after_each();
  }
  return truth;
}

}  // namespace fleetmap::vehicle_agent::node::testing
