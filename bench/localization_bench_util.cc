#include "bench/localization_bench_util.h"

#include <cstdio>
#include <cstdlib>
#include <utility>
#include <variant>

namespace fleetmap::bench {
namespace {

std::string WorldsDir() { return std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/"; }

sim::World OrDie(core::Result<sim::World> world) {
  if (!world.ok()) {
    std::fprintf(stderr, "localization_bench: %s\n", world.status().ToString().c_str());
    std::exit(1);
  }
  return std::move(world).value();
}

}  // namespace

sim::World LoadWorld(const std::string& scenario_file) {
  return OrDie(sim::World::Load(WorldsDir() + scenario_file));
}

sim::World ParseWorld(const std::string& yaml) {
  auto scenario = sim::ParseScenario(yaml, "study.yaml");
  if (!scenario.ok()) return OrDie(scenario.status());
  return OrDie(
      sim::World::Create(std::move(scenario).value(), LoadWorld("addition.yaml").static_map()));
}

std::vector<SensorStep> RecordSensorSteps(const sim::World& world, size_t vehicle, double end_s) {
  sim::Simulator simulator(&world);
  std::vector<SensorStep> steps;
  core::OdometrySample odom;
  while (auto e = simulator.Next()) {
    if (sim::EventTime(*e) > end_s) break;
    if (const auto* o = std::get_if<sim::OdometryEvent>(&*e); o && o->vehicle == vehicle)
      odom = {o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps};
    if (const auto* s = std::get_if<sim::ScanEvent>(&*e); s && s->vehicle == vehicle)
      steps.push_back({odom, *s});
  }
  return steps;
}

const sim::World& Addition() {
  static const sim::World world = LoadWorld("addition.yaml");
  return world;
}

const core::Pose2& Mount() { return Addition().scenario().vehicles[0].scanner_mount; }

}  // namespace fleetmap::bench
