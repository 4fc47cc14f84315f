// A simulated world: a static map (any map_server map) plus what happens in it: semi-static
// objects that appear and disappear, dynamic actors walking or driving along paths, and the
// vehicles with their scanners and routes. Loaded from a scenario YAML (docs/scenario.md).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "sim/route.h"
#include "sim/scanner_model.h"

namespace fleetmap::sim {

// A pallet, a parked vehicle, a box: a solid polygon present in [appear_s, disappear_s).
struct SemiStaticObject {
  std::string id;
  std::string kind = "pallet";
  std::vector<Eigen::Vector2d> polygon_m;  // in the static map frame, metres
  std::string shape_field = "polygon";     // "rect" or "polygon": how the file gave it
  double appear_s = 0.0;
  double disappear_s = std::numeric_limits<double>::infinity();
  int line = 0;  // where it is defined in the scenario file, for messages
  bool PresentAt(double t_s) const { return t_s >= appear_s && t_s < disappear_s; }
};

// A person or a forklift: a disc moving along a polyline. Actors are never part of the map.
struct DynamicActor {
  std::string id;
  std::string kind = "person";
  double radius_m = 0.25;
  std::vector<Eigen::Vector2d> path_m;
  RouteOptions motion;  // speed, loop, start time
  int line = 0;
};

// Thrun's odometry motion model noise (Probabilistic Robotics, table 5.6): standard
// deviations grow with the rotation and translation of each increment.
struct OdometryNoise {
  double rot_per_rot = 0.02;           // rad of rotation noise per rad turned
  double rot_per_trans_rad_m = 0.01;   // rad of rotation noise per metre driven
  double trans_per_trans = 0.02;       // m of translation noise per metre driven
  double trans_per_rot_m_rad = 0.005;  // m of translation noise per rad turned
  double rate_hz = 50.0;               // odometry messages per second
  // The noise above is drawn anew for every increment, so at 50 Hz it averages out: over a
  // metre it is a tenth of its per-metre value. Real odometry errs systematically too (a
  // wheel's radius a little off, a wheelbase that is not the nominal one), and over the
  // 0.3-2 m spans of the SLAM benchmark logs it is off by 3-7 % of the distance and 3-4 deg
  // per metre (median; docs/scenario.md). These two are drawn once per vehicle and run:
  double scale_sigma = 0.0;                // distance reported x (1 + s), s ~ N(0, this)
  double heading_drift_sigma_rad_m = 0.0;  // a turn of b rad per metre driven, b ~ N(0, this)
};

// A noisy pose from an external localization system, for vehicles that already localize.
struct ExternalPoseNoise {
  bool enabled = false;
  double sigma_xy_m = 0.03;
  double sigma_theta_rad = 0.01;
  double rate_hz = 10.0;
};

struct VehicleSpec {
  std::string id;
  ScannerModel scanner;
  core::Pose2 scanner_mount;  // scanner pose in the vehicle frame
  std::vector<Eigen::Vector2d> route_m;
  RouteOptions motion;
  OdometryNoise odometry;
  ExternalPoseNoise external_pose;
  int line = 0;
};

struct Scenario {
  std::string name;
  std::string path;      // the scenario file, for messages
  std::string map_yaml;  // resolved path of the static map
  double duration_s = 300.0;
  uint32_t seed = 1;
  std::vector<SemiStaticObject> objects;
  std::vector<DynamicActor> actors;
  std::vector<VehicleSpec> vehicles;
};

// Reads a scenario file. Every error names the file, the line and the field. Checks that need
// the map (objects inside it, routes clear of walls) are done by World::Create.
core::Result<Scenario> LoadScenario(const std::string& path);
core::Result<Scenario> ParseScenario(const std::string& yaml_text, const std::string& name);

// The scenario as YAML that LoadScenario reads back (objects as polygons), naming the map as
// `map_reference`; SaveScenario writes it to `path`, the map relative to the file's folder.
std::string ScenarioToYaml(const Scenario& scenario, const std::string& map_reference);
core::Status SaveScenario(const Scenario& scenario, const std::string& path);

// Metres from p to the polygon's outline; 0 inside it.
double DistanceToPolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

// An axis-aligned or rotated rectangle as a polygon.
std::vector<Eigen::Vector2d> RectanglePolygon(const Eigen::Vector2d& center,
                                              const Eigen::Vector2d& size_m, double yaw_rad);

}  // namespace fleetmap::sim
