#include "sim/worldgen/world_generator.h"

#include <string>

namespace fleetmap::sim::worldgen {
namespace {

constexpr double kMaxBuildingSideM = 150.0;

core::Status CheckSide(const char* name, double v) {
  if (v == 0.0 || (v >= kMinBuildingSideM && v <= kMaxBuildingSideM)) return core::OkStatus();
  return core::InvalidArgument(std::string(name) + " must be 0 (the style's choice) or within " +
                               std::to_string(kMinBuildingSideM) + " and " +
                               std::to_string(kMaxBuildingSideM) + " m, not " + std::to_string(v));
}

}  // namespace

core::Status WorldOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(CheckSide("length_m", length_m));
  FLEETMAP_RETURN_IF_ERROR(CheckSide("width_m", width_m));
  return render.Validate();
}

core::Result<GeneratedWorld> GenerateWorld(const WorldOptions& o) {
  FLEETMAP_RETURN_IF_ERROR(o.Validate());
  // Independent streams: the size, the plan and the look do not shift each other's draws.
  Rng root(o.seed);
  Rng size_rng = root.Fork(), plan_rng = root.Fork(), look_rng = root.Fork();
  const SizeRange range = DefaultSize(o.style);
  const double length =
      o.length_m > 0 ? o.length_m : size_rng.Uniform(range.min_length_m, range.max_length_m);
  const double width =
      o.width_m > 0 ? o.width_m : size_rng.Uniform(range.min_width_m, range.max_width_m);
  GeneratedWorld world;
  world.plan = DrawBuilding(o.style, length, width, plan_rng);
  FLEETMAP_ASSIGN_OR_RETURN(world.map, RenderFloorPlan(world.plan, o.render, look_rng));
  return world;
}

}  // namespace fleetmap::sim::worldgen
