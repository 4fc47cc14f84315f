// Scenario -> YAML, the inverse of scenario_loader.cc: what LoadScenario reads back as the
// same scenario (docs/scenario.md). Writes every field a generated scenario sets.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>

#include "core/io/file_io.h"
#include "sim/scenario.h"

namespace fleetmap::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Metres to the millimetre: enough for a map, and short files.
double Mm(double v) { return std::round(v * 1000.0) / 1000.0; }

void Points(YAML::Emitter& e, const std::vector<Eigen::Vector2d>& points) {
  e << YAML::Flow << YAML::BeginSeq;
  for (const Eigen::Vector2d& p : points)
    e << YAML::Flow << YAML::BeginSeq << Mm(p.x()) << Mm(p.y()) << YAML::EndSeq;
  e << YAML::EndSeq;
}

void Motion(YAML::Emitter& e, const RouteOptions& m) {
  e << YAML::Key << "speed_mps" << YAML::Value << m.speed_mps;
  e << YAML::Key << "angular_speed_radps" << YAML::Value << m.angular_speed_radps;
  e << YAML::Key << "loop" << YAML::Value << m.loop;
  if (m.start_s != 0) e << YAML::Key << "start_s" << YAML::Value << Mm(m.start_s);
  if (m.dwell_s > 0) e << YAML::Key << "dwell_s" << YAML::Value << Mm(m.dwell_s);
}

// The odometry's noise where it is not the default, all of it (a reader sees the whole model).
void OdometryNoiseIfSet(YAML::Emitter& e, const OdometryNoise& n) {
  const OdometryNoise d;
  if (n.rot_per_rot == d.rot_per_rot && n.rot_per_trans_rad_m == d.rot_per_trans_rad_m &&
      n.trans_per_trans == d.trans_per_trans && n.trans_per_rot_m_rad == d.trans_per_rot_m_rad &&
      n.rate_hz == d.rate_hz && n.scale_sigma == d.scale_sigma &&
      n.heading_drift_sigma_rad_m == d.heading_drift_sigma_rad_m)
    return;
  e << YAML::Key << "odometry_noise" << YAML::Value << YAML::Flow << YAML::BeginMap;
  e << YAML::Key << "rot_per_rot" << YAML::Value << n.rot_per_rot;
  e << YAML::Key << "rot_per_trans_rad_m" << YAML::Value << n.rot_per_trans_rad_m;
  e << YAML::Key << "trans_per_trans" << YAML::Value << n.trans_per_trans;
  e << YAML::Key << "trans_per_rot_m_rad" << YAML::Value << n.trans_per_rot_m_rad;
  e << YAML::Key << "rate_hz" << YAML::Value << n.rate_hz;
  e << YAML::Key << "scale_sigma" << YAML::Value << n.scale_sigma;
  e << YAML::Key << "heading_drift_sigma_rad_m" << YAML::Value << n.heading_drift_sigma_rad_m;
  e << YAML::EndMap;
}

}  // namespace

std::string ScenarioToYaml(const Scenario& s, const std::string& map_reference) {
  YAML::Emitter e;
  e.SetDoublePrecision(9);  // 150.000 m to the millimetre, without binary noise
  e << YAML::BeginMap;
  e << YAML::Key << "name" << YAML::Value << s.name;
  e << YAML::Key << "map" << YAML::Value << map_reference;
  e << YAML::Key << "duration_s" << YAML::Value << s.duration_s;
  e << YAML::Key << "seed" << YAML::Value << s.seed;
  e << YAML::Key << "objects" << YAML::Value << YAML::BeginSeq;
  for (const SemiStaticObject& o : s.objects) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "id" << YAML::Value << o.id;
    e << YAML::Key << "kind" << YAML::Value << o.kind << YAML::Key << "polygon" << YAML::Value;
    Points(e, o.polygon_m);
    if (o.appear_s > 0) e << YAML::Key << "appear_s" << YAML::Value << Mm(o.appear_s);
    if (std::isfinite(o.disappear_s))
      e << YAML::Key << "disappear_s" << YAML::Value << Mm(o.disappear_s);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;
  e << YAML::Key << "actors" << YAML::Value << YAML::BeginSeq;
  for (const DynamicActor& a : s.actors) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "id" << YAML::Value << a.id;
    e << YAML::Key << "kind" << YAML::Value << a.kind;
    e << YAML::Key << "radius_m" << YAML::Value << a.radius_m << YAML::Key << "path" << YAML::Value;
    Points(e, a.path_m);
    Motion(e, a.motion);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;
  e << YAML::Key << "vehicles" << YAML::Value << YAML::BeginSeq;
  for (const VehicleSpec& v : s.vehicles) {
    e << YAML::BeginMap << YAML::Key << "id" << YAML::Value << v.id;
    e << YAML::Key << "scanner" << YAML::Value << v.scanner.name;
    e << YAML::Key << "scanner_mount" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << Mm(v.scanner_mount.x_m) << Mm(v.scanner_mount.y_m) << Mm(v.scanner_mount.theta_rad / kDeg)
      << YAML::EndSeq;
    e << YAML::Key << "route" << YAML::Value;
    Points(e, v.route_m);
    Motion(e, v.motion);
    OdometryNoiseIfSet(e, v.odometry);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

core::Status SaveScenario(const Scenario& s, const std::string& path) {
  namespace fs = std::filesystem;
  // The map as the loader resolves it: relative to the scenario's folder.
  std::error_code ec;
  const fs::path folder = fs::absolute(fs::path(path), ec).parent_path();
  fs::path map = fs::absolute(fs::path(s.map_yaml), ec);
  const fs::path relative = map.lexically_relative(folder);
  const std::string reference = relative.empty() ? map.string() : relative.string();
  return core::WriteFileAtomically(path, ScenarioToYaml(s, reference));
}

}  // namespace fleetmap::sim
