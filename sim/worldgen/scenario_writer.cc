#include "sim/worldgen/scenario_writer.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "sim/route.h"
#include "sim/world.h"
#include "sim/worldgen/free_space.h"

namespace fleetmap::sim::worldgen {
namespace {

using Route = std::vector<Eigen::Vector2d>;

constexpr double kDeg = M_PI / 180.0;
constexpr const char* kScanners[] = {"S300", "microScan3", "TiM571", "LMS111"};
constexpr int kTries = 400;

// The legs of a looping route, the closing one included.
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> Legs(const Route& r) {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> legs;
  for (size_t i = 0; i < r.size(); ++i) legs.push_back({r[i], r[(i + 1) % r.size()]});
  return legs;
}

double LoopLength(const Route& r) {
  double length = 0;
  for (const auto& [a, b] : Legs(r)) length += (b - a).norm();
  return length;
}

// Samples every 0.1 m along a segment.
template <typename Fn>
bool AllAlong(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Fn ok) {
  const int steps = static_cast<int>((b - a).norm() / 0.1) + 1;
  for (int i = 0; i <= steps; ++i)
    if (!ok(a + (b - a) * (static_cast<double>(i) / steps))) return false;
  return true;
}

// A loop through up to four goals spread over the free space near a random start, at most
// `budget_m` long so that the vehicle passes every place more than twice in the run.
core::Result<Route> PlanLoop(const FreeSpace& space, double budget_m, Rng& rng) {
  double radius = budget_m / 4;
  for (int attempt = 0; attempt < 60; ++attempt) {
    Route goals = {space.RandomPoint(rng)};
    for (int g = 1; g < 4; ++g) {
      Eigen::Vector2d best;
      double best_spread = -1;
      for (int c = 0; c < 200; ++c) {
        const Eigen::Vector2d p = space.RandomPoint(rng);
        if ((p - goals[0]).norm() > radius) continue;
        double spread = 1e18;
        for (const auto& q : goals) spread = std::min(spread, (p - q).norm());
        if (spread > best_spread) best_spread = spread, best = p;
      }
      if (best_spread >= 2.0) goals.push_back(best);
    }
    if (goals.size() < 2) continue;
    Route route;
    bool planned = true;
    for (size_t i = 0; i < goals.size() && planned; ++i) {
      const Route legs = space.Path(goals[i], goals[(i + 1) % goals.size()]);
      planned = !legs.empty();
      for (size_t k = route.empty() ? 0 : 1; k < legs.size(); ++k) route.push_back(legs[k]);
    }
    if (!planned) continue;
    route.pop_back();  // the loop closes on its first waypoint
    route.erase(std::unique(route.begin(), route.end(),
                            [](const auto& a, const auto& b) { return (a - b).norm() < 1e-6; }),
                route.end());
    const double length = route.size() >= 2 ? LoopLength(route) : 0.0;
    if (length > budget_m) radius *= 0.8;
    if (route.size() >= 2 && length >= 4.0 && length <= budget_m) return route;
  }
  return core::FailedPrecondition("no loop route of 4 to " + std::to_string(budget_m) +
                                  " m fits the free space");
}

double LoopBudget(const ScenarioOptions& o) {
  return o.max_loop_m > 0 ? o.max_loop_m : o.vehicle_speed_mps * o.duration_s / 2.5;
}

struct Placement {
  Eigen::Vector2d at, along;  // a point on a route and the route's direction there
  size_t vehicle;
};

Placement OnARoute(const std::vector<Route>& routes, Rng& rng, double min_leg_m = 0.0) {
  for (int i = 0; i < kTries; ++i) {
    const size_t v = static_cast<size_t>(rng.Int(0, static_cast<int>(routes.size()) - 1));
    const auto legs = Legs(routes[v]);
    const auto& [a, b] = legs[static_cast<size_t>(rng.Int(0, static_cast<int>(legs.size()) - 1))];
    if ((b - a).norm() < std::max(min_leg_m, 1e-3)) continue;
    return {a + (b - a) * rng.Uniform(0.1, 0.9), (b - a).normalized(), v};
  }
  return {routes[0][0], (routes[0][1] - routes[0][0]).normalized(), 0};
}

// What of the scenario found no room.
enum class Part { kNone, kObject, kPerson, kForklift };

class Writer {
 public:
  Writer(const core::OccupancyGrid& map, const ScenarioOptions& o)
      : map_(map), o_(o), rng_(o.seed) {}

  core::Result<sim::Scenario> Write(const std::string& map_yaml) {
    sim::Scenario s;
    s.name = "generated";
    s.map_yaml = map_yaml;
    s.duration_s = o_.duration_s;
    s.seed = o_.seed;
    auto drive = FreeSpace::Of(map_, o_.vehicle_clearance_m);
    if (!drive.ok()) return drive.status().WithContext("vehicles");
    auto floor = FreeSpace::Of(map_, 0.05);
    if (!floor.ok()) return floor.status();
    const double budget = LoopBudget(o_);
    for (int v = 0; v < o_.vehicles; ++v) {
      auto route = PlanLoop(*drive, budget, rng_);
      if (!route.ok()) return route.status();
      routes_.push_back(*route);
      sim::VehicleSpec spec;
      spec.id = "v" + std::to_string(v + 1);
      FLEETMAP_ASSIGN_OR_RETURN(spec.scanner, sim::FindScannerModel(kScanners[v % 4]));
      spec.scanner_mount = core::Pose2(0.3, 0.0, 0.0);
      spec.route_m = *route;
      spec.motion.speed_mps = o_.vehicle_speed_mps;
      spec.motion.loop = true;
      spec.motion.start_s = 5.0 * v;
      spec.odometry.scale_sigma = o_.odometry_scale_sigma;
      spec.odometry.heading_drift_sigma_rad_m = o_.odometry_heading_drift_sigma_rad_m;
      periods_.push_back(sim::Route(*route, spec.motion).period_s());
      s.vehicles.push_back(spec);
    }
    for (int i = 0; i < o_.objects_added + o_.objects_removed; ++i) {
      const bool removed = i >= o_.objects_added;
      auto object = PlaceObject(*floor, s.objects, removed);
      if (!object.ok()) return Failed(Part::kObject, object.status());
      object->id = object->kind + (removed ? "_taken_" : "_") + std::to_string(i + 1);
      s.objects.push_back(*object);
    }
    for (int i = 0; i < o_.people + o_.forklifts; ++i) {
      const bool forklift = i >= o_.people;
      auto actor = forklift ? PlaceForklift(s.objects) : PlacePerson(s.objects, i % 2 == 1);
      if (!actor.ok()) return Failed(forklift ? Part::kForklift : Part::kPerson, actor.status());
      actor->id = actor->kind + "_" + std::to_string(i + 1);
      s.actors.push_back(*actor);
    }
    return s;
  }

  Part failed() const { return failed_; }

 private:
  core::Status Failed(Part part, const core::Status& why) {
    failed_ = part;
    return why;
  }

  bool ClearOfRoutes(const std::vector<Eigen::Vector2d>& polygon, double gap_m) const {
    for (const Route& r : routes_)
      for (const auto& [a, b] : Legs(r))
        if (!AllAlong(a, b, [&](const Eigen::Vector2d& q) {
              return sim::DistanceToPolygon(polygon, q) >= gap_m;
            }))
          return false;
    return true;
  }

  core::Result<sim::SemiStaticObject> PlaceObject(const FreeSpace& floor,
                                                  const std::vector<sim::SemiStaticObject>& placed,
                                                  bool removed) {
    const double gap = o_.vehicle_clearance_m + o_.object_gap_m;
    for (int i = 0; i < kTries; ++i) {
      const Placement p = OnARoute(routes_, rng_);
      // Pallets; where none fits (small, cluttered rooms), boxes.
      const bool box = i >= kTries / 2;
      const Eigen::Vector2d size =
          box ? Eigen::Vector2d(0.6, 0.4) : Eigen::Vector2d(1.2, rng_.Chance(0.5) ? 0.8 : 1.0);
      const Eigen::Vector2d normal(-p.along.y(), p.along.x());
      const double side = rng_.Chance(0.5) ? 1.0 : -1.0;
      const Eigen::Vector2d centre =
          p.at + normal * side * (gap + size.y() / 2 + rng_.Uniform(0.0, 3.0));
      const double yaw = std::atan2(p.along.y(), p.along.x()) + rng_.Uniform(-10.0, 10.0) * kDeg;
      sim::SemiStaticObject o;
      o.kind = box ? "box" : "pallet";
      o.polygon_m = sim::RectanglePolygon(centre, size, yaw);
      bool on_floor = true;
      for (double u = -0.5; u <= 0.5 && on_floor; u += 0.25)
        for (double w = -0.5; w <= 0.5 && on_floor; w += 0.25)
          on_floor = floor.Contains(
              core::Pose2(centre.x(), centre.y(), yaw).Apply({u * size.x(), w * size.y()}));
      if (!on_floor || !ClearOfRoutes(o.polygon_m, gap)) continue;
      bool apart = true;
      for (const auto& other : placed)
        apart = apart && sim::DistanceToPolygon(other.polygon_m, centre) > 1.5;
      if (!apart) continue;
      // Changed while the vehicle that passes it has at least one and a half loops to go.
      const double D = o_.duration_s, last = D - 1.5 * periods_[p.vehicle];
      if (removed) {
        o.disappear_s = rng_.Uniform(0.2 * D, std::max(0.25 * D, last));
      } else {
        o.appear_s = rng_.Uniform(0.1 * D, std::max(0.15 * D, last));
      }
      return o;
    }
    return core::FailedPrecondition("no room for a pallet or a box beside the routes (" +
                                    std::to_string(gap) + " m from every route, on free floor)");
  }

  bool ClearOfObjects(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius_m,
                      const std::vector<sim::SemiStaticObject>& objects) const {
    return AllAlong(a, b, [&](const Eigen::Vector2d& q) {
      for (const auto& o : objects)
        if (sim::DistanceToPolygon(o.polygon_m, q) < radius_m + 0.1) return false;
      return true;
    });
  }

  // The free space for a clearance, made on first use: every person shares one.
  const core::Result<FreeSpace>& SpaceFor(double clearance_m) {
    auto it = spaces_.find(clearance_m);
    if (it == spaces_.end())
      it = spaces_.emplace(clearance_m, FreeSpace::Of(map_, clearance_m)).first;
    return it->second;
  }

  // Across a route and back (along it where the room is too narrow), turning at each end;
  // `stands`: waits a few seconds there too.
  core::Result<sim::DynamicActor> PlacePerson(const std::vector<sim::SemiStaticObject>& objects,
                                              bool stands) {
    sim::DynamicActor a;
    a.kind = "person";
    a.radius_m = 0.25;
    const auto& walk = SpaceFor(a.radius_m + 0.1);
    if (!walk.ok()) return walk.status().WithContext("people");
    for (int i = 0; i < kTries; ++i) {
      const Placement p = OnARoute(routes_, rng_);
      // Across the route where there is room; in corridors too narrow for that, along it.
      const Eigen::Vector2d normal(-p.along.y(), p.along.x());
      const Eigen::Vector2d way = i < kTries / 2 ? normal : p.along;
      const Eigen::Vector2d from = p.at - way * rng_.Uniform(0.8, 4.0);
      const Eigen::Vector2d to = p.at + way * rng_.Uniform(0.8, 4.0);
      if (!walk->SegmentInside(from, to) || !ClearOfObjects(from, to, a.radius_m, objects))
        continue;
      a.path_m = {from, to};
      a.motion.speed_mps = rng_.Uniform(0.8, 1.4);
      a.motion.angular_speed_radps = 2.0;
      a.motion.loop = true;
      a.motion.start_s = UnderWaySince(0.3 * o_.duration_s);
      if (stands) a.motion.dwell_s = rng_.Uniform(2.0, 5.0);
      return a;
    }
    return core::FailedPrecondition("no room for a person crossing a route");
  }

  // A start in the past (negative, up to `max_s` ago): the actor is somewhere along its loop
  // when the scenario starts, so that actors do not move in step, and none stands still longer
  // than its dwell. One that waited tens of seconds at its first point would be a parked
  // vehicle, which the map rightly adds.
  double UnderWaySince(double max_s) { return -rng_.Uniform(0.0, max_s); }

  // Along a route, stopping for a few seconds at each end.
  // A forklift where one fits, else a cart (narrow corridors: offices, hospitals).
  core::Result<sim::DynamicActor> PlaceForklift(const std::vector<sim::SemiStaticObject>& objects) {
    auto forklift = PlaceVehicleActor(objects, "forklift", 0.8);
    return forklift.ok() ? forklift : PlaceVehicleActor(objects, "cart", 0.45);
  }

  core::Result<sim::DynamicActor> PlaceVehicleActor(
      const std::vector<sim::SemiStaticObject>& objects, const char* kind, double radius_m) {
    sim::DynamicActor a;
    a.kind = kind;
    a.radius_m = radius_m;
    const auto& drive = SpaceFor(a.radius_m + 0.1);
    if (!drive.ok()) return drive.status().WithContext("forklifts");
    for (int i = 0; i < kTries; ++i) {
      const Placement p = OnARoute(routes_, rng_, 6.0);
      const Eigen::Vector2d from = p.at - p.along * rng_.Uniform(2.5, 6.0);
      const Eigen::Vector2d to = p.at + p.along * rng_.Uniform(2.5, 6.0);
      if (!drive->SegmentInside(from, to) || !ClearOfObjects(from, to, a.radius_m, objects))
        continue;
      a.path_m = {from, to};
      a.motion.speed_mps = 1.5;
      a.motion.angular_speed_radps = 1.0;
      a.motion.loop = true;
      a.motion.start_s = UnderWaySince(0.2 * o_.duration_s);
      a.motion.dwell_s = rng_.Uniform(3.0, 8.0);
      return a;
    }
    return core::FailedPrecondition("no room for a forklift (" + std::to_string(a.radius_m + 0.1) +
                                    " m clearance) on a route");
  }

  const core::OccupancyGrid& map_;
  const ScenarioOptions& o_;
  Rng rng_;
  std::vector<Route> routes_;
  std::vector<double> periods_;
  std::map<double, core::Result<FreeSpace>> spaces_;  // by clearance: each made once
  Part failed_ = Part::kNone;
};

}  // namespace

core::Status ScenarioOptions::Validate() const {
  if (vehicles < 1 || vehicles > 5) return core::InvalidArgument("vehicles must be 1 to 5");
  if (!(duration_s > 0) || !(vehicle_speed_mps > 0) || !(vehicle_clearance_m > 0) ||
      !(object_gap_m >= 0) || !(max_loop_m >= 0) || !(odometry_scale_sigma >= 0) ||
      !(odometry_heading_drift_sigma_rad_m >= 0))
    return core::InvalidArgument(
        "duration_s, vehicle_speed_mps and vehicle_clearance_m must be positive, object_gap_m, "
        "max_loop_m and the odometry sigmas not negative");
  if (objects_added < 0 || objects_removed < 0 || people < 0 || forklifts < 0)
    return core::InvalidArgument("counts of objects, people and forklifts must not be negative");
  return core::OkStatus();
}

namespace {

core::Result<sim::Scenario> WriteChecked(const core::OccupancyGrid& map,
                                         const std::string& map_yaml,
                                         const ScenarioOptions& options, Part& failed) {
  Writer writer(map, options);
  auto scenario = writer.Write(map_yaml);
  failed = writer.failed();
  if (!scenario.ok()) return scenario;
  // The simulator's own checks (routes clear of walls, objects inside the map, people clear of
  // objects) hold for what was written.
  auto world = sim::World::Create(*scenario, map);
  if (!world.ok()) return world.status().WithContext("generated scenario");
  return scenario;
}

// The next smaller scenario to try where `failed` found no room in `o`; false when nothing
// smaller would help.
bool Smaller(const ScenarioOptions& asked, Part failed, ScenarioOptions& o) {
  if (failed == Part::kForklift) {
    o.forklifts = 0;  // a cart was tried too
    return true;
  }
  if (failed == Part::kPerson && o.people > 1) {
    --o.people;
    return true;
  }
  if (failed != Part::kObject) return false;
  if (o.vehicles > 1) {
    --o.vehicles;
    return true;
  }
  if (o.objects_added > 1) {
    --o.objects_added;
    return true;
  }
  if (LoopBudget(o) > LoopBudget(asked) / 3) {
    o.max_loop_m = LoopBudget(o) / 2;
    return true;
  }
  return false;
}

std::string Fitted(const ScenarioOptions& asked, const ScenarioOptions& used) {
  std::string fitted;
  const auto add = [&](const std::string& what) { fitted += (fitted.empty() ? "" : ", ") + what; };
  if (used.vehicles != asked.vehicles)
    add(std::to_string(used.vehicles) + " vehicle(s) instead of " + std::to_string(asked.vehicles));
  if (used.objects_added != asked.objects_added)
    add(std::to_string(used.objects_added) + " object(s) appearing instead of " +
        std::to_string(asked.objects_added));
  if (LoopBudget(used) != LoopBudget(asked))
    add("loops up to " + std::to_string(static_cast<int>(LoopBudget(used))) + " m");
  if (used.people != asked.people)
    add(std::to_string(used.people) + " people instead of " + std::to_string(asked.people));
  if (used.forklifts != asked.forklifts) add("no forklift");
  return fitted;
}

}  // namespace

core::Result<WrittenScenario> WriteScenarioFor(const core::OccupancyGrid& map,
                                               const std::string& map_yaml,
                                               const ScenarioOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  ScenarioOptions tried = options;
  Part failed = Part::kNone;
  auto scenario = WriteChecked(map, map_yaml, tried, failed);
  // The first refusal is the one reported: it names what the asked-for fleet lacks.
  const core::Status first = scenario.status();
  while (!scenario.ok() && options.fit_to_floor && Smaller(options, failed, tried))
    scenario = WriteChecked(map, map_yaml, tried, failed);
  if (!scenario.ok()) return first;
  return WrittenScenario{std::move(*scenario), Fitted(options, tried)};
}

}  // namespace fleetmap::sim::worldgen
