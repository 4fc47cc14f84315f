// Scenario YAML -> Scenario. Field by field, so that every message can say where it is.
#include <cmath>

#include "core/io/yaml_reader.h"
#include "sim/scenario.h"

namespace fleetmap::sim {
namespace {

using core::Result;
using core::Status;
using core::YamlReader;

constexpr double kDeg = M_PI / 180.0;

Status Positive(const YamlReader& r, const YAML::Node& parent, const std::string& key,
                const std::string& field, double value) {
  if (value > 0) return core::OkStatus();
  return r.Error(parent[key] ? parent[key] : parent, field, "must be positive");
}

Status NonNegative(const YamlReader& r, const YAML::Node& parent, const std::string& key,
                   const std::string& field, double value) {
  if (value >= 0) return core::OkStatus();
  return r.Error(parent[key] ? parent[key] : parent, field, "must be >= 0");
}

Status ReadMotion(const YamlReader& r, const YAML::Node& n, const std::string& f, RouteOptions& m) {
  FLEETMAP_ASSIGN_OR_RETURN(m.speed_mps, r.Number(n, "speed_mps", f + ".speed_mps", m.speed_mps));
  FLEETMAP_RETURN_IF_ERROR(Positive(r, n, "speed_mps", f + ".speed_mps", m.speed_mps));
  FLEETMAP_ASSIGN_OR_RETURN(
      m.angular_speed_radps,
      r.Number(n, "angular_speed_radps", f + ".angular_speed_radps", m.angular_speed_radps));
  FLEETMAP_RETURN_IF_ERROR(
      Positive(r, n, "angular_speed_radps", f + ".angular_speed_radps", m.angular_speed_radps));
  FLEETMAP_ASSIGN_OR_RETURN(m.loop, r.GetOr<bool>(n, "loop", f + ".loop", m.loop));
  FLEETMAP_ASSIGN_OR_RETURN(m.start_s, r.Number(n, "start_s", f + ".start_s", m.start_s));
  FLEETMAP_ASSIGN_OR_RETURN(m.dwell_s, r.Number(n, "dwell_s", f + ".dwell_s", m.dwell_s));
  if (m.dwell_s < 0) return r.Error(n["dwell_s"], f + ".dwell_s", "must not be negative");
  return core::OkStatus();
}

Result<SemiStaticObject> ReadObject(const YamlReader& r, const YAML::Node& n,
                                    const std::string& f) {
  SemiStaticObject o;
  FLEETMAP_ASSIGN_OR_RETURN(o.id, r.Get<std::string>(n, "id", f + ".id"));
  FLEETMAP_ASSIGN_OR_RETURN(o.kind, r.GetOr<std::string>(n, "kind", f + ".kind", o.kind));
  if (n["rect"]) {
    const YAML::Node rect = n["rect"];
    // yaml-cpp throws on a key looked up in a scalar.
    if (!rect.IsMap()) return r.Error(rect, f + ".rect", "must be a map with center and size");
    Eigen::Vector2d center, size;
    FLEETMAP_ASSIGN_OR_RETURN(center, r.Point(rect["center"], f + ".rect.center"));
    FLEETMAP_ASSIGN_OR_RETURN(size, r.Point(rect["size"], f + ".rect.size"));
    if (size.x() <= 0 || size.y() <= 0) return r.Error(rect, f + ".rect.size", "must be positive");
    double yaw_deg;
    FLEETMAP_ASSIGN_OR_RETURN(yaw_deg, r.Number(rect, "yaw_deg", f + ".rect.yaw_deg", 0.0));
    o.polygon_m = RectanglePolygon(center, size, yaw_deg * kDeg);
    o.shape_field = "rect";
  } else if (n["polygon"]) {
    FLEETMAP_ASSIGN_OR_RETURN(o.polygon_m, r.Points(n["polygon"], f + ".polygon", 3));
  } else {
    return r.Error(n, f, "needs a 'rect' or a 'polygon'");
  }
  FLEETMAP_ASSIGN_OR_RETURN(o.appear_s, r.Number(n, "appear_s", f + ".appear_s", 0.0));
  FLEETMAP_ASSIGN_OR_RETURN(o.disappear_s,
                            r.Number(n, "disappear_s", f + ".disappear_s", o.disappear_s));
  if (o.disappear_s <= o.appear_s) {
    return r.Error(n, f + ".disappear_s", "must be later than appear_s");
  }
  return o;
}

Result<DynamicActor> ReadActor(const YamlReader& r, const YAML::Node& n, const std::string& f) {
  DynamicActor a;
  a.motion.speed_mps = 1.2;  // walking pace
  a.motion.angular_speed_radps = 2.0;
  FLEETMAP_ASSIGN_OR_RETURN(a.id, r.Get<std::string>(n, "id", f + ".id"));
  FLEETMAP_ASSIGN_OR_RETURN(a.kind, r.GetOr<std::string>(n, "kind", f + ".kind", a.kind));
  FLEETMAP_ASSIGN_OR_RETURN(a.radius_m, r.Number(n, "radius_m", f + ".radius_m", a.radius_m));
  FLEETMAP_RETURN_IF_ERROR(Positive(r, n, "radius_m", f + ".radius_m", a.radius_m));
  FLEETMAP_ASSIGN_OR_RETURN(a.path_m, r.Points(n["path"], f + ".path", 2));
  FLEETMAP_RETURN_IF_ERROR(ReadMotion(r, n, f, a.motion));
  return a;
}

Result<VehicleSpec> ReadVehicle(const YamlReader& r, const YAML::Node& n, const std::string& f) {
  VehicleSpec v;
  FLEETMAP_ASSIGN_OR_RETURN(v.id, r.Get<std::string>(n, "id", f + ".id"));
  std::string scanner;
  FLEETMAP_ASSIGN_OR_RETURN(scanner, r.GetOr<std::string>(n, "scanner", f + ".scanner", "S300"));
  auto model = FindScannerModel(scanner);
  if (!model.ok()) return r.Error(n["scanner"], f + ".scanner", model.status().message());
  v.scanner = *model;
  if (n["scanner_mount"]) {
    std::vector<double> m;
    FLEETMAP_ASSIGN_OR_RETURN(m, r.Numbers(n["scanner_mount"], f + ".scanner_mount", 3));
    v.scanner_mount = core::Pose2(m[0], m[1], m[2] * kDeg);
  }
  FLEETMAP_ASSIGN_OR_RETURN(v.route_m, r.Points(n["route"], f + ".route", 2));
  for (size_t i = 0; i + 1 < v.route_m.size(); ++i) {
    if ((v.route_m[i + 1] - v.route_m[i]).norm() < 1e-6) {
      return r.Error(n["route"][i + 1], f + ".route[" + std::to_string(i + 1) + "]",
                     "repeats the previous waypoint");
    }
  }
  FLEETMAP_RETURN_IF_ERROR(ReadMotion(r, n, f, v.motion));
  if (const YAML::Node o = n["odometry_noise"]) {
    const std::string g = f + ".odometry_noise";
    OdometryNoise& d = v.odometry;
    FLEETMAP_ASSIGN_OR_RETURN(d.rot_per_rot,
                              r.Number(o, "rot_per_rot", g + ".rot_per_rot", d.rot_per_rot));
    FLEETMAP_ASSIGN_OR_RETURN(
        d.rot_per_trans_rad_m,
        r.Number(o, "rot_per_trans_rad_m", g + ".rot_per_trans_rad_m", d.rot_per_trans_rad_m));
    FLEETMAP_ASSIGN_OR_RETURN(
        d.trans_per_trans,
        r.Number(o, "trans_per_trans", g + ".trans_per_trans", d.trans_per_trans));
    FLEETMAP_ASSIGN_OR_RETURN(
        d.trans_per_rot_m_rad,
        r.Number(o, "trans_per_rot_m_rad", g + ".trans_per_rot_m_rad", d.trans_per_rot_m_rad));
    FLEETMAP_ASSIGN_OR_RETURN(d.rate_hz, r.Number(o, "rate_hz", g + ".rate_hz", d.rate_hz));
    FLEETMAP_RETURN_IF_ERROR(Positive(r, o, "rate_hz", g + ".rate_hz", d.rate_hz));
    FLEETMAP_ASSIGN_OR_RETURN(d.scale_sigma,
                              r.Number(o, "scale_sigma", g + ".scale_sigma", d.scale_sigma));
    FLEETMAP_ASSIGN_OR_RETURN(
        d.heading_drift_sigma_rad_m,
        r.Number(o, "heading_drift_sigma_rad_m", g + ".heading_drift_sigma_rad_m",
                 d.heading_drift_sigma_rad_m));
    FLEETMAP_RETURN_IF_ERROR(NonNegative(r, o, "scale_sigma", g + ".scale_sigma", d.scale_sigma));
    FLEETMAP_RETURN_IF_ERROR(NonNegative(r, o, "heading_drift_sigma_rad_m",
                                         g + ".heading_drift_sigma_rad_m",
                                         d.heading_drift_sigma_rad_m));
  }
  if (const YAML::Node e = n["external_pose"]) {
    const std::string g = f + ".external_pose";
    ExternalPoseNoise& x = v.external_pose;
    x.enabled = true;
    FLEETMAP_ASSIGN_OR_RETURN(x.sigma_xy_m,
                              r.Number(e, "sigma_xy_m", g + ".sigma_xy_m", x.sigma_xy_m));
    FLEETMAP_ASSIGN_OR_RETURN(
        x.sigma_theta_rad,
        r.Number(e, "sigma_theta_rad", g + ".sigma_theta_rad", x.sigma_theta_rad));
    FLEETMAP_ASSIGN_OR_RETURN(x.rate_hz, r.Number(e, "rate_hz", g + ".rate_hz", x.rate_hz));
    FLEETMAP_RETURN_IF_ERROR(Positive(r, e, "rate_hz", g + ".rate_hz", x.rate_hz));
  }
  return v;
}

template <typename T, typename ReadFn>
Status ReadList(const YamlReader& r, const std::string& key, ReadFn read, std::vector<T>& out) {
  const YAML::Node list = r.root()[key];
  if (!list) return core::OkStatus();
  if (!list.IsSequence()) return r.Error(list, key, "must be a list");
  for (size_t i = 0; i < list.size(); ++i) {
    auto item = read(r, list[i], key + "[" + std::to_string(i) + "]");
    if (!item.ok()) return item.status();
    for (const T& other : out) {
      if (other.id == item->id) {
        return r.Error(list[i], key + "[" + std::to_string(i) + "].id",
                       "'" + item->id + "' is used twice");
      }
    }
    item->line = list[i].Mark().line + 1;
    out.push_back(std::move(item).value());
  }
  return core::OkStatus();
}

Result<Scenario> Read(const YamlReader& r) {
  Scenario s;
  s.path = r.path();
  const YAML::Node& root = r.root();
  FLEETMAP_ASSIGN_OR_RETURN(s.name, r.GetOr<std::string>(root, "name", "name", "scenario"));
  std::string map;
  FLEETMAP_ASSIGN_OR_RETURN(map, r.Get<std::string>(root, "map", "map"));
  s.map_yaml = r.Resolve(map);
  FLEETMAP_ASSIGN_OR_RETURN(s.duration_s, r.Number(root, "duration_s", "duration_s", s.duration_s));
  FLEETMAP_RETURN_IF_ERROR(Positive(r, root, "duration_s", "duration_s", s.duration_s));
  FLEETMAP_ASSIGN_OR_RETURN(s.seed, r.GetOr<uint32_t>(root, "seed", "seed", s.seed));
  FLEETMAP_RETURN_IF_ERROR(ReadList(r, "objects", ReadObject, s.objects));
  FLEETMAP_RETURN_IF_ERROR(ReadList(r, "actors", ReadActor, s.actors));
  FLEETMAP_RETURN_IF_ERROR(ReadList(r, "vehicles", ReadVehicle, s.vehicles));
  if (s.vehicles.empty()) return r.Error(root, "vehicles", "at least one vehicle is needed");
  return s;
}

}  // namespace

Result<Scenario> LoadScenario(const std::string& path) {
  auto reader = YamlReader::Load(path);
  if (!reader.ok()) return reader.status();
  return Read(*reader);
}

Result<Scenario> ParseScenario(const std::string& yaml_text, const std::string& name) {
  auto reader = YamlReader::FromString(yaml_text, name);
  if (!reader.ok()) return reader.status();
  return Read(*reader);
}

std::vector<Eigen::Vector2d> RectanglePolygon(const Eigen::Vector2d& center,
                                              const Eigen::Vector2d& size_m, double yaw_rad) {
  const core::Pose2 pose(center.x(), center.y(), yaw_rad);
  const double hx = size_m.x() / 2, hy = size_m.y() / 2;
  return {pose.Apply({-hx, -hy}), pose.Apply({hx, -hy}), pose.Apply({hx, hy}),
          pose.Apply({-hx, hy})};
}

}  // namespace fleetmap::sim
