// The simulated world at any time: the static map, the semi-static objects present then and
// the actors' positions. Knows the truth the evaluation scores against.
#pragma once

#include <vector>

#include "core/map/occupancy_grid.h"
#include "sim/route.h"
#include "sim/scenario.h"

namespace fleetmap::sim {

// A semi-static object appearing ("added", also for objects there from the start: the static
// map does not have them) or disappearing ("removed").
struct ChangeEvent {
  double t_s = 0.0;
  size_t object = 0;  // index into scenario().objects
  bool added = true;
};

class World {
 public:
  // Checks the scenario against the map: objects inside it, vehicle routes clear of walls and
  // inside the map, and returns the world. Errors name the scenario file and the field.
  static core::Result<World> Create(Scenario scenario, core::OccupancyGrid static_map);
  // Loads the scenario and the static map it names, or `map_override` when not empty.
  static core::Result<World> Load(const std::string& scenario_path,
                                  const std::string& map_override = "");

  const Scenario& scenario() const { return scenario_; }
  const core::OccupancyGrid& static_map() const { return static_map_; }
  const core::GridGeometry& geometry() const { return static_map_.geometry(); }

  // Cells inside each object's polygon (row-major indices), in scenario order.
  const std::vector<std::vector<int64_t>>& object_cells() const { return object_cells_; }
  // Per cell: 1 + the index of the object covering it, 0 for none (the later object wins).
  const std::vector<int32_t>& object_raster() const { return object_raster_; }

  // Cells that block beams at `t_s`: the static map's occupied cells and present objects.
  std::vector<uint8_t> SolidAt(double t_s) const;
  // The true map at `t_s`: the static map with the present objects' cells occupied.
  core::OccupancyGrid TrueMapAt(double t_s) const;
  // Every change in time order (within the scenario's duration).
  std::vector<ChangeEvent> ChangeEvents() const;
  // Sorted times at which an object appears or disappears (within the scenario's duration).
  std::vector<double> ChangeTimes() const;

  RouteState VehicleStateAt(size_t vehicle, double t_s) const;
  Eigen::Vector2d ActorPositionAt(size_t actor, double t_s) const;

 private:
  World(Scenario scenario, core::OccupancyGrid static_map);
  core::Status Check() const;
  core::Status CheckActorClearOfObjects(size_t actor) const;

  Scenario scenario_;
  core::OccupancyGrid static_map_;
  std::vector<uint8_t> static_solid_;
  std::vector<std::vector<int64_t>> object_cells_;
  std::vector<int32_t> object_raster_;
  std::vector<Route> vehicle_routes_;
  std::vector<Route> actor_routes_;
};

}  // namespace fleetmap::sim
