// fleetmap-sim: runs a scenario and publishes every vehicle's scans and odometry over LCM,
// in real time or at a speed factor, so that agents run exactly as on vehicles. See --help.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "core/command_line.h"
#include "lcmtypes/convert.h"
#include "sim/lcm_bridge/sim_publisher.h"

namespace {

using namespace fleetmap;

volatile std::sig_atomic_t g_stop = 0;
void OnSignal(int) { g_stop = 1; }

struct Args {
  std::string scenario, map, url = lcmtypes::kDefaultSensorUrl;
  double speed = 1.0, duration = -1.0, epoch = -1.0;
  bool truth = true, list_vehicles = false;
  std::string vehicles;  // comma-separated ids; empty: all
};

// Reads the command line into `a`. No value: go on; otherwise the exit status.
std::optional<int> Parse(int argc, char** argv, Args& a) {
  CLI::App app(
      "Simulates the scenario's vehicles and publishes, per vehicle ID: SCAN_<ID>\n"
      "(laser_scan_t), ODOM_<ID> (odometry_t), EXTPOSE_<ID> (vehicles with an external\n"
      "localization) and TRUTH_<ID> (ground-truth pose, pose_with_covariance_t).\n"
      "Stops cleanly on SIGINT/SIGTERM. Exit status: 0 done, 1 bad scenario or LCM failure,\n"
      "2 usage errors. The multicast URL needs a route (loopback: ip route add 224.0.0.0/4\n"
      "dev lo).",
      "fleetmap-sim");
  core::AddVersionFlag(app);
  app.add_option("--scenario", a.scenario, "scenario YAML (docs/scenario.md)")->required();
  app.add_option("--map", a.map, "static map instead of the scenario's");
  app.add_option("--speed", a.speed,
                 "simulated seconds per wall-clock second; 0 = as fast as possible")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  app.add_option("--duration", a.duration,
                 "stop after this many simulated seconds (default: the scenario's duration)")
      ->check(core::Finite());
  app.add_option("--lcm-url", a.url, "where to publish")->capture_default_str();
  app.add_option("--epoch", a.epoch,
                 "add this many seconds to every time stamp (default: the wall clock at start)")
      ->check(core::Finite());
  bool no_truth = false;
  app.add_flag("--no-truth", no_truth, "do not publish TRUTH_<ID>");
  app.add_option("--vehicles", a.vehicles,
                 "publish only these vehicles, A,B (e.g. one simulator per vehicle host in a LAN "
                 "experiment; the world, with every vehicle in it, is the same; default: all)");
  app.add_flag("--list-vehicles", a.list_vehicles,
               "print a line `ID X Y THETA MX MY MTHETA` per vehicle (metres, radians: its pose "
               "at time 0, an agent's --initial-pose, and its scanner mount, the agent's "
               "--scanner-mount), a line `map FILE` (the static map), and exit");
  const auto exit_status = core::ParseCommandLine(app, argc, argv);
  a.truth = !no_truth;
  return exit_status;
}

double WallNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const auto exit_status = Parse(argc, argv, args)) return *exit_status;
  auto world = sim::World::Load(args.scenario, args.map);
  if (!world.ok()) {
    std::fprintf(stderr, "fleetmap-sim: %s\n", world.status().ToString().c_str());
    return 1;
  }
  if (args.list_vehicles) {
    for (size_t i = 0; i < world->scenario().vehicles.size(); ++i) {
      const core::Pose2 p = world->VehicleStateAt(i, 0.0).pose;
      const core::Pose2 m = world->scenario().vehicles[i].scanner_mount;
      std::printf("%s %.4f %.4f %.6f %.4f %.4f %.6f\n", world->scenario().vehicles[i].id.c_str(),
                  p.x_m, p.y_m, p.theta_rad, m.x_m, m.y_m, m.theta_rad);
    }
    std::printf("map %s\n",
                args.map.empty() ? world->scenario().map_yaml.c_str() : args.map.c_str());
    return 0;
  }
  lcm::LCM lcm(args.url);
  if (!lcm.good()) {
    std::fprintf(stderr,
                 "fleetmap-sim: cannot open LCM at %s (for multicast on one host: "
                 "ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo)\n",
                 args.url.c_str());
    return 1;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  // Which vehicles to publish.
  std::vector<bool> publish(world->scenario().vehicles.size(), args.vehicles.empty());
  for (size_t start = 0; !args.vehicles.empty() && start <= args.vehicles.size();) {
    const size_t comma = std::min(args.vehicles.find(',', start), args.vehicles.size());
    const std::string id = args.vehicles.substr(start, comma - start);
    bool found = false;
    for (size_t v = 0; v < publish.size(); ++v) {
      if (world->scenario().vehicles[v].id == id) publish[v] = found = true;
    }
    if (!found) {
      std::fprintf(stderr, "fleetmap-sim: --vehicles: the scenario has no vehicle '%s'\n",
                   id.c_str());
      return 2;
    }
    start = comma + 1;
  }
  const double duration = args.duration >= 0 ? args.duration : world->scenario().duration_s;
  sim::lcm_bridge::SimPublisherOptions options;
  options.epoch_s = args.epoch >= 0 ? args.epoch : WallNow();
  options.publish_truth = args.truth;
  sim::Simulator simulator(&*world);
  sim::lcm_bridge::SimPublisher publisher(&lcm, &*world, options);
  std::fprintf(stderr, "fleetmap-sim: %s, %zu vehicles, %.0f s at %gx on %s\n",
               args.scenario.c_str(), world->scenario().vehicles.size(), duration, args.speed,
               args.url.c_str());
  const auto start = std::chrono::steady_clock::now();
  double next_progress_s = 10.0;
  while (!g_stop) {
    auto event = simulator.Next();
    if (!event || sim::EventTime(*event) > duration) break;
    const double t = sim::EventTime(*event);
    if (args.speed > 0) {
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>(t / args.speed)));
    }
    if (publish[std::visit([](const auto& e) { return e.vehicle; }, *event)])
      publisher.Publish(*event);
    if (t >= next_progress_s) {
      std::fprintf(stderr, "  %.0f s simulated, %lld messages, %.1f MB\n", t,
                   (long long)publisher.counters().messages, publisher.counters().bytes / 1e6);
      next_progress_s += 10.0;
    }
  }
  const auto& c = publisher.counters();
  std::fprintf(stderr,
               "fleetmap-sim: %s after %.1f simulated s: %lld messages, %lld bytes, %lld failed\n",
               g_stop ? "stopped" : "done", simulator.now_s(), (long long)c.messages,
               (long long)c.bytes, (long long)c.failures);
  return c.failures == 0 ? 0 : 1;
}
