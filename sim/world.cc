#include "sim/world.h"

#include <algorithm>
#include <cmath>

#include "core/map/map_io.h"

namespace fleetmap::sim {
namespace {

// Even-odd rule on the cell centre: a cell belongs to the polygon when its centre is inside,
// so a 1 m square at 5 cm covers exactly 20 x 20 cells.
bool Inside(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

std::vector<int64_t> RasterizePolygon(const core::GridGeometry& g,
                                      const std::vector<Eigen::Vector2d>& polygon) {
  std::vector<Eigen::Vector2d> cells_poly;  // the polygon in continuous cell coordinates
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  for (const Eigen::Vector2d& p : polygon) {
    cells_poly.push_back(g.WorldToGrid(p));
    lo = lo.cwiseMin(cells_poly.back());
    hi = hi.cwiseMax(cells_poly.back());
  }
  std::vector<int64_t> cells;
  for (int y = std::max(0, int(std::floor(lo.y()))); y <= std::min(g.height() - 1, int(hi.y()));
       ++y)
    for (int x = std::max(0, int(std::floor(lo.x()))); x <= std::min(g.width() - 1, int(hi.x()));
         ++x)
      if (Inside(cells_poly, {x + 0.5, y + 0.5})) cells.push_back(g.Index({x, y}));
  return cells;
}

std::string Field(const char* list, size_t i, const std::string& field) {
  return std::string(list) + "[" + std::to_string(i) + "]." + field;
}

// "x 1.00..2.00 m, y 3.00..4.00 m": the bounding box of points.
std::string Extent(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  for (const Eigen::Vector2d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  char text[96];
  std::snprintf(text, sizeof(text), "x %.2f..%.2f m, y %.2f..%.2f m", lo.x(), hi.x(), lo.y(),
                hi.y());
  return text;
}

std::string MapExtent(const core::GridGeometry& g) {
  const double w = g.width() * g.resolution_m(), h = g.height() * g.resolution_m();
  std::vector<Eigen::Vector2d> corners;
  for (const Eigen::Vector2d& c :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0), Eigen::Vector2d(0, h), Eigen::Vector2d(w, h)})
    corners.push_back(g.origin().Apply(c));
  return Extent(corners);
}

}  // namespace

double DistanceToPolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  if (Inside(poly, p)) return 0.0;
  double best = 1e18;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d d = poly[i] - poly[j];
    const double t = std::clamp((p - poly[j]).dot(d) / std::max(d.squaredNorm(), 1e-12), 0.0, 1.0);
    best = std::min(best, (poly[j] + t * d - p).norm());
  }
  return best;
}

World::World(Scenario scenario, core::OccupancyGrid static_map)
    : scenario_(std::move(scenario)), static_map_(std::move(static_map)) {
  const core::GridGeometry& g = static_map_.geometry();
  static_solid_.resize(static_cast<size_t>(g.num_cells()));
  const core::TriStateClassifier classify;
  for (size_t i = 0; i < static_solid_.size(); ++i)
    static_solid_[i] = classify(static_map_.cells()[i]) == core::CellState::kOccupied;
  object_raster_.assign(static_solid_.size(), 0);
  for (size_t k = 0; k < scenario_.objects.size(); ++k) {
    object_cells_.push_back(RasterizePolygon(g, scenario_.objects[k].polygon_m));
    for (int64_t c : object_cells_.back()) object_raster_[c] = static_cast<int32_t>(k + 1);
  }
  for (const VehicleSpec& v : scenario_.vehicles) vehicle_routes_.emplace_back(v.route_m, v.motion);
  for (const DynamicActor& a : scenario_.actors) actor_routes_.emplace_back(a.path_m, a.motion);
}

core::Result<World> World::Create(Scenario scenario, core::OccupancyGrid static_map) {
  World world(std::move(scenario), std::move(static_map));
  FLEETMAP_RETURN_IF_ERROR(world.Check());
  return world;
}

core::Result<World> World::Load(const std::string& scenario_path, const std::string& map_override) {
  auto scenario = LoadScenario(scenario_path);
  if (!scenario.ok()) return scenario.status();
  if (!map_override.empty()) scenario->map_yaml = map_override;
  auto map = core::LoadMapServerMap(scenario->map_yaml);
  if (!map.ok()) return map.status().WithContext(scenario_path + ": map");
  return Create(std::move(scenario).value(), std::move(map->grid));
}

core::Status World::Check() const {
  const core::GridGeometry& g = geometry();
  auto inside = [&](const Eigen::Vector2d& p) { return g.Contains(g.WorldToCell(p)); };
  auto error = [&](int line, const std::string& field, const std::string& what) {
    return core::InvalidArgument(scenario_.path + ":" + std::to_string(line) + ": " + field + ": " +
                                 what);
  };
  for (size_t k = 0; k < scenario_.objects.size(); ++k) {
    const SemiStaticObject& o = scenario_.objects[k];
    for (const Eigen::Vector2d& p : o.polygon_m) {
      if (!inside(p))
        return error(o.line, Field("objects", k, o.shape_field),
                     "object '" + o.id + "' spans " + Extent(o.polygon_m) + ", beyond the map (" +
                         MapExtent(g) + ")");
    }
  }
  for (size_t v = 0; v < scenario_.vehicles.size(); ++v) {
    const auto& route = scenario_.vehicles[v].route_m;
    for (size_t i = 0; i + 1 < route.size() + (scenario_.vehicles[v].motion.loop ? 1 : 0); ++i) {
      const Eigen::Vector2d a = route[i], b = route[(i + 1) % route.size()];
      const int steps = static_cast<int>((b - a).norm() / (g.resolution_m() / 2)) + 1;
      for (int s = 0; s <= steps; ++s) {
        const Eigen::Vector2d p = a + (b - a) * (double(s) / steps);
        const core::CellIndex c = g.WorldToCell(p);
        const std::string field = Field("vehicles", v, "route") + " leg " + std::to_string(i);
        if (!g.Contains(c)) return error(scenario_.vehicles[v].line, field, "leaves the map");
        if (static_solid_[g.Index(c)]) {
          char where[64];
          std::snprintf(where, sizeof(where), "(%.2f, %.2f)", p.x(), p.y());
          return error(scenario_.vehicles[v].line, field,
                       std::string("runs through a wall at ") + where);
        }
      }
    }
  }
  for (size_t a = 0; a < scenario_.actors.size(); ++a) {
    for (const Eigen::Vector2d& p : scenario_.actors[a].path_m) {
      if (!inside(p))
        return error(scenario_.actors[a].line, Field("actors", a, "path"), "leaves the map");
    }
    FLEETMAP_RETURN_IF_ERROR(CheckActorClearOfObjects(a));
  }
  return core::OkStatus();
}

// People and forklifts walk around pallets, not through them: a path that crosses an object
// (at any time of the run) is a mistake in the scenario.
core::Status World::CheckActorClearOfObjects(size_t a) const {
  const DynamicActor& actor = scenario_.actors[a];
  const auto& path = actor.path_m;
  const double step = geometry().resolution_m() / 2;
  for (size_t i = 0; i + 1 < path.size() + (actor.motion.loop ? 1 : 0); ++i) {
    const Eigen::Vector2d from = path[i], to = path[(i + 1) % path.size()];
    const int steps = static_cast<int>((to - from).norm() / step) + 1;
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector2d p = from + (to - from) * (double(s) / steps);
      for (const SemiStaticObject& o : scenario_.objects) {
        if (DistanceToPolygon(o.polygon_m, p) >= actor.radius_m) continue;
        char where[64];
        std::snprintf(where, sizeof(where), "(%.2f, %.2f)", p.x(), p.y());
        return core::InvalidArgument(
            scenario_.path + ":" + std::to_string(actor.line) + ": " + Field("actors", a, "path") +
            " leg " + std::to_string(i) + ": " + actor.kind + " '" + actor.id + "' (radius " +
            std::to_string(actor.radius_m).substr(0, 4) + " m) runs into object '" + o.id +
            "' at " + where + ": route it around");
      }
    }
  }
  return core::OkStatus();
}

std::vector<uint8_t> World::SolidAt(double t_s) const {
  std::vector<uint8_t> solid = static_solid_;
  for (size_t k = 0; k < scenario_.objects.size(); ++k) {
    if (!scenario_.objects[k].PresentAt(t_s)) continue;
    for (int64_t c : object_cells_[k]) solid[c] = 1;
  }
  return solid;
}

core::OccupancyGrid World::TrueMapAt(double t_s) const {
  core::OccupancyGrid truth = static_map_;
  const core::GridGeometry& g = geometry();
  for (size_t k = 0; k < scenario_.objects.size(); ++k) {
    if (!scenario_.objects[k].PresentAt(t_s)) continue;
    for (int64_t c : object_cells_[k])
      truth.SetState({int(c % g.width()), int(c / g.width())}, core::CellState::kOccupied);
  }
  return truth;
}

std::vector<double> World::ChangeTimes() const {
  std::vector<double> times;
  for (const SemiStaticObject& o : scenario_.objects) {
    if (o.appear_s > 0 && o.appear_s < scenario_.duration_s) times.push_back(o.appear_s);
    if (o.disappear_s < scenario_.duration_s) times.push_back(o.disappear_s);
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

std::vector<ChangeEvent> World::ChangeEvents() const {
  std::vector<ChangeEvent> events;
  for (size_t k = 0; k < scenario_.objects.size(); ++k) {
    const SemiStaticObject& o = scenario_.objects[k];
    if (o.appear_s < scenario_.duration_s) events.push_back({std::max(0.0, o.appear_s), k, true});
    if (o.disappear_s < scenario_.duration_s) events.push_back({o.disappear_s, k, false});
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const ChangeEvent& a, const ChangeEvent& b) { return a.t_s < b.t_s; });
  return events;
}

RouteState World::VehicleStateAt(size_t vehicle, double t_s) const {
  return vehicle_routes_[vehicle].StateAt(t_s);
}

Eigen::Vector2d World::ActorPositionAt(size_t actor, double t_s) const {
  return actor_routes_[actor].StateAt(t_s).pose.translation();
}

}  // namespace fleetmap::sim
