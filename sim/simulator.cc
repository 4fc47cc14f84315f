#include "sim/simulator.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fleetmap::sim {
namespace {

// Ray against disc: distance along the unit direction to the first intersection, or kNoHit.
double RayDisc(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& c,
               double r) {
  const Eigen::Vector2d oc = o - c;
  const double b = oc.dot(d), q = oc.squaredNorm() - r * r;
  const double disc = b * b - q;
  if (disc < 0) return core::kNoHit;
  const double t = -b - std::sqrt(disc);
  return t >= 0 ? t : (q < 0 ? 0.0 : core::kNoHit);
}

}  // namespace

double EventTime(const SimEvent& event) {
  return std::visit(
      [](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, ScanEvent>) {
          return e.scan.stamp_s;
        } else {
          return e.stamp_s;
        }
      },
      event);
}

Simulator::Simulator(const World* world)
    : world_(world),
      caster_(world->geometry()),
      observations_(world->scenario().objects.size(), world->scenario().vehicles.size(),
                    &world->object_raster()),
      change_times_(world->ChangeTimes()) {
  caster_.SetSolid(world_->SolidAt(0.0));
  const auto& vehicles = world_->scenario().vehicles;
  for (size_t v = 0; v < vehicles.size(); ++v) {
    VehicleClock c;
    // Stagger the scanners a little, as real ones are not synchronised.
    c.next_scan_s = vehicles[v].scanner.period_s() * (0.1 + 0.8 * v / vehicles.size());
    c.next_odom_s = 0.0;
    c.next_external_s = vehicles[v].external_pose.enabled ? 0.0 : core::kNoHit;
    c.last_true_pose = world_->VehicleStateAt(v, 0.0).pose;
    c.rng.seed(world_->scenario().seed * 7919u + static_cast<uint32_t>(v));
    // Drawn only when asked for, so that scenarios without it keep their random streams.
    const OdometryNoise& n = vehicles[v].odometry;
    if (n.scale_sigma > 0)
      c.odom_scale += std::normal_distribution<double>(0.0, n.scale_sigma)(c.rng);
    if (n.heading_drift_sigma_rad_m > 0)
      c.odom_heading_drift_rad_m =
          std::normal_distribution<double>(0.0, n.heading_drift_sigma_rad_m)(c.rng);
    clocks_.push_back(c);
  }
  const core::GridGeometry& g = world_->geometry();
  for (const auto& cells : world_->object_cells()) {
    std::array<int, 4> box{g.width(), g.height(), -1, -1};
    for (int64_t c : cells) {
      const int x = int(c % g.width()), y = int(c / g.width());
      box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
    }
    object_boxes_.push_back(box);
  }
}

std::optional<SimEvent> Simulator::Next() {
  size_t best_v = 0;
  int best_kind = -1;
  double best_t = core::kNoHit;
  for (size_t v = 0; v < clocks_.size(); ++v) {
    const double times[3] = {clocks_[v].next_scan_s, clocks_[v].next_odom_s,
                             clocks_[v].next_external_s};
    for (int k = 0; k < 3; ++k) {
      if (times[k] < best_t) best_t = times[k], best_v = v, best_kind = k;
    }
  }
  if (best_kind < 0 || best_t > world_->scenario().duration_s) return std::nullopt;
  now_s_ = best_t;
  const VehicleSpec& spec = world_->scenario().vehicles[best_v];
  VehicleClock& clock = clocks_[best_v];
  switch (best_kind) {
    case 0:
      clock.next_scan_s += spec.scanner.period_s();
      return MakeScan(best_v, best_t);
    case 1:
      clock.next_odom_s += 1.0 / spec.odometry.rate_hz;
      return MakeOdometry(best_v, best_t);
    default:
      clock.next_external_s += 1.0 / spec.external_pose.rate_hz;
      return MakeExternalPose(best_v, best_t);
  }
}

void Simulator::UpdateSolid(double t) {
  bool changed = false;
  while (next_change_ < change_times_.size() && change_times_[next_change_] <= t) {
    ++next_change_;
    changed = true;
  }
  if (changed) caster_.SetSolid(world_->SolidAt(t));
}

ScanEvent Simulator::MakeScan(size_t v, double t) {
  UpdateSolid(t);
  const VehicleSpec& spec = world_->scenario().vehicles[v];
  const ScannerModel& m = spec.scanner;
  ScanEvent e;
  e.vehicle = v;
  e.true_base_pose = world_->VehicleStateAt(v, t).pose;
  e.true_scanner_pose = e.true_base_pose * spec.scanner_mount;
  core::LaserScan& scan = e.scan;
  scan.stamp_s = t;
  scan.angle_min_rad = m.angle_min_rad();
  scan.angle_increment_rad = m.increment_rad;
  scan.range_min_m = m.range_min_m;
  scan.range_max_m = m.range_max_m;
  scan.scan_period_s = m.period_s();
  scan.ranges_m.resize(static_cast<size_t>(m.num_beams));
  const Eigen::Vector2d origin = e.true_scanner_pose.translation();
  for (int i = 0; i < m.num_beams; ++i) {
    const double angle = e.true_scanner_pose.theta_rad + scan.angle(static_cast<size_t>(i));
    const core::RayHit hit = caster_.Cast(origin, angle, m.range_max_m);
    const double range = std::min(hit.range_m, CastActors(origin, angle, m.range_max_m, t));
    RecordBeam(v, origin, angle, hit, range, t);
    scan.ranges_m[i] = range < m.range_max_m ? static_cast<float>(range) : INFINITY;
  }
  ApplyScannerNoise(m, clocks_[v].rng, scan.ranges_m);
  ++scans_produced_;
  return e;
}

double Simulator::CastActors(const Eigen::Vector2d& origin, double angle, double range,
                             double t) const {
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  double best = core::kNoHit;
  for (size_t a = 0; a < world_->scenario().actors.size(); ++a) {
    const double r = world_->scenario().actors[a].radius_m;
    const double hit = RayDisc(origin, d, world_->ActorPositionAt(a, t), r);
    if (hit < range) best = std::min(best, hit);
  }
  return best;
}

// Records, for the evaluation, which object cells this beam hit or passed through. Only
// beams that cross an object's bounding box are walked cell by cell.
void Simulator::RecordBeam(size_t v, const Eigen::Vector2d& origin, double angle,
                           const core::RayHit& hit, double range, double t) {
  const core::GridGeometry& g = world_->geometry();
  const auto& objects = world_->scenario().objects;
  const auto& raster = world_->object_raster();
  if (std::isfinite(hit.range_m) && hit.range_m <= range) {
    const int64_t cell = g.Index(hit.cell);
    if (raster[cell] > 0) {
      observations_.RecordHit(cell, t);
      const size_t k = static_cast<size_t>(raster[cell] - 1);
      if (objects[k].PresentAt(t)) observations_.RecordAppearSeen(k, v, t);
    }
  }
  const double res = g.resolution_m();
  const Eigen::Vector2d o = g.WorldToGrid(origin);
  const double a = angle - g.origin().theta_rad;
  const Eigen::Vector2d d(std::cos(a), std::sin(a));
  const double t_end = (std::isfinite(range) ? range : core::kNoHit) / res;
  for (size_t k = 0; k < object_boxes_.size(); ++k) {
    const auto& b = object_boxes_[k];
    // Slab test against the box [x0, x1+1] x [y0, y1+1].
    double t0 = 0.0, t1 = std::min(t_end, world_->scenario().vehicles[v].scanner.range_max_m / res);
    for (int axis = 0; axis < 2 && t0 <= t1; ++axis) {
      const double lo = b[axis], hi = b[axis + 2] + 1.0;
      if (std::abs(d[axis]) < 1e-12) {
        if (o[axis] < lo || o[axis] > hi) t0 = t1 + 1;
        continue;
      }
      double ta = (lo - o[axis]) / d[axis], tb = (hi - o[axis]) / d[axis];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 > t1) continue;
    for (double s = t0; s < t1; s += 0.25) {  // quarter-cell steps inside a small box
      const core::CellIndex c{int(std::floor(o.x() + d.x() * s)),
                              int(std::floor(o.y() + d.y() * s))};
      if (!g.Contains(c) || c == hit.cell) continue;
      const int64_t cell = g.Index(c);
      if (raster[cell] != int32_t(k + 1)) continue;
      observations_.RecordPass(cell, t);
      if (t >= objects[k].disappear_s) observations_.RecordDisappearSeen(k, v, t);
    }
  }
}

void Simulator::ApplyScannerNoise(const ScannerModel& m, std::mt19937& rng,
                                  std::vector<float>& ranges) const {
  std::normal_distribution<double> noise(0.0, m.range_sigma_m);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Mixed pixels first, on the noise-free depths, so edges are judged on the true jump.
  for (size_t i = 0; i + 1 < ranges.size(); ++i) {
    const float a = ranges[i], b = ranges[i + 1];
    if (std::isfinite(a) && std::isfinite(b) && std::abs(a - b) > m.mixed_pixel_min_jump_m &&
        u(rng) < m.mixed_pixel_probability) {
      ranges[i] = static_cast<float>(a + (b - a) * u(rng));
    }
  }
  for (float& r : ranges) {
    if (u(rng) < m.dropout_probability) {
      r = INFINITY;
    } else if (std::isfinite(r)) {
      r = static_cast<float>(std::max(m.range_min_m, r + noise(rng)));
    }
  }
}

OdometryEvent Simulator::MakeOdometry(size_t v, double t) {
  const VehicleSpec& spec = world_->scenario().vehicles[v];
  VehicleClock& c = clocks_[v];
  const RouteState truth = world_->VehicleStateAt(v, t);
  // Thrun's odometry model: the true increment as rotate-translate-rotate, each perturbed.
  const core::Pose2 inc = core::Between(c.last_true_pose, truth.pose);
  const double trans = std::hypot(inc.x_m, inc.y_m);
  const double rot1 = trans > 1e-6 ? std::atan2(inc.y_m, inc.x_m) : 0.0;
  const double rot2 = core::NormalizeAngle(inc.theta_rad - rot1);
  const OdometryNoise& n = spec.odometry;
  auto gauss = [&](double sigma) {
    return sigma > 0 ? std::normal_distribution<double>(0.0, sigma)(c.rng) : 0.0;
  };
  const double drift = 0.5 * c.odom_heading_drift_rad_m * trans;  // half before, half after
  const double r1 =
      rot1 + drift + gauss(n.rot_per_rot * std::abs(rot1) + n.rot_per_trans_rad_m * trans);
  const double tr =
      trans * c.odom_scale +
      gauss(n.trans_per_trans * trans + n.trans_per_rot_m_rad * (std::abs(rot1) + std::abs(rot2)));
  const double r2 =
      rot2 + drift + gauss(n.rot_per_rot * std::abs(rot2) + n.rot_per_trans_rad_m * trans);
  c.odom_pose = c.odom_pose * core::Pose2(0, 0, r1) * core::Pose2(tr, 0, r2);
  c.last_true_pose = truth.pose;
  return {v, t, c.odom_pose, truth.v_mps, truth.omega_radps, truth.pose};
}

ExternalPoseEvent Simulator::MakeExternalPose(size_t v, double t) {
  const ExternalPoseNoise& n = world_->scenario().vehicles[v].external_pose;
  std::normal_distribution<double> xy(0.0, n.sigma_xy_m), th(0.0, n.sigma_theta_rad);
  const core::Pose2 truth = world_->VehicleStateAt(v, t).pose;
  auto& rng = clocks_[v].rng;
  return {v, t,
          core::Pose2(truth.x_m + xy(rng), truth.y_m + xy(rng),
                      core::NormalizeAngle(truth.theta_rad + th(rng)))};
}

}  // namespace fleetmap::sim
