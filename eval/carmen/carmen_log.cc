#include "eval/carmen/carmen_log.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace fleetmap::eval::carmen {
namespace {

// Reads whitespace-separated numbers, remembering whether any failed.
class Fields {
 public:
  explicit Fields(const std::string& line) : in_(line) {}
  double Number() {
    double v = 0;
    if (!(in_ >> v) || !std::isfinite(v)) ok_ = false;
    return v;
  }
  int Count(int max) {
    const double v = Number();
    if (v < 0 || v > max || v != std::floor(v)) ok_ = false;
    return ok_ ? static_cast<int>(v) : 0;
  }
  // Three numbers read in order (function arguments are evaluated in no fixed order).
  core::Pose2 Pose() {
    const double x = Number(), y = Number(), theta = Number();
    return {x, y, theta};
  }
  std::string Word() {
    std::string w;
    if (!(in_ >> w)) ok_ = false;
    return w;
  }
  bool ok() const { return ok_; }

 private:
  std::istringstream in_;
  bool ok_ = true;
};

constexpr int kMaxReadings = 10000;

core::Status Bad(int line_number, const std::string& what) {
  return core::InvalidArgument("line " + std::to_string(line_number) + ": " + what);
}

// FLASER num [ranges] x y theta odom_x odom_y odom_theta ipc_timestamp host logger_timestamp
core::Status ParseFlaser(Fields& f, int n, const CarmenReadOptions& o, CarmenLog& log) {
  LaserRecord r;
  const int count = f.Count(kMaxReadings);
  // 180 and 360 readings span 180 deg exclusive of the last; 181 and 361 inclusive.
  r.scan.angle_min_rad = -M_PI / 2;
  r.scan.angle_increment_rad = count % 2 == 1 ? M_PI / (count - 1) : M_PI / count;
  r.scan.range_min_m = 0.0;
  r.scan.range_max_m = o.flaser_max_range_m;
  for (int i = 0; i < count; ++i) r.scan.ranges_m.push_back(static_cast<float>(f.Number()));
  for (int i = 0; i < 3; ++i) f.Number();  // x y theta: the same as odom in these logs
  r.odom_pose = f.Pose();
  r.stamp_s = f.Number();
  if (!f.ok() || count < 2) return Bad(n, "malformed FLASER");
  r.scan.stamp_s = r.stamp_s;
  log.lasers.push_back(std::move(r));
  return core::OkStatus();
}

// ROBOTLASER1 type start fov res max_range accuracy remission_mode num [ranges] num_rem
// [remissions] laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv fwd side turn
// ipc_timestamp host logger_timestamp
core::Status ParseRobotLaser(Fields& f, int n, CarmenLog& log) {
  LaserRecord r;
  f.Number();
  r.scan.angle_min_rad = f.Number();
  f.Number();  // field of view
  r.scan.angle_increment_rad = f.Number();
  r.scan.range_max_m = f.Number();
  f.Number();
  f.Number();
  const int count = f.Count(kMaxReadings);
  for (int i = 0; i < count; ++i) r.scan.ranges_m.push_back(static_cast<float>(f.Number()));
  const int remissions = f.Count(kMaxReadings);
  for (int i = 0; i < remissions; ++i) f.Number();
  const core::Pose2 laser = f.Pose();
  r.odom_pose = f.Pose();
  r.laser_in_base = core::Between(r.odom_pose, laser);
  for (int i = 0; i < 5; ++i) f.Number();
  r.stamp_s = f.Number();
  if (!f.ok() || count < 2) return Bad(n, "malformed ROBOTLASER1");
  r.scan.stamp_s = r.stamp_s;
  log.lasers.push_back(std::move(r));
  return core::OkStatus();
}

}  // namespace

core::Status ParseCarmenLine(const std::string& line, int n, const CarmenReadOptions& o,
                             CarmenLog& log) {
  Fields f(line);
  const std::string type = f.Word();
  if (type == "FLASER") return ParseFlaser(f, n, o, log);
  if (type == "ROBOTLASER1") return ParseRobotLaser(f, n, log);
  if (type == "ODOM") {
    OdomRecord r;
    r.pose = f.Pose();
    r.v_mps = f.Number();
    r.omega_radps = f.Number();
    f.Number();  // acceleration
    r.stamp_s = f.Number();
    if (!f.ok()) return Bad(n, "malformed ODOM");
    log.odometry.push_back(r);
    return core::OkStatus();
  }
  ++log.skipped_lines;
  return core::OkStatus();
}

int InterpolateOdometryAtScans(CarmenLog& log, double scan_latency_s) {
  const auto& odo = log.odometry;
  if (odo.size() < 2 || !std::isfinite(scan_latency_s)) return 0;
  int done = 0;
  for (LaserRecord& r : log.lasers) {
    const double taken_s = r.stamp_s - scan_latency_s;
    auto it = std::lower_bound(odo.begin(), odo.end(), taken_s,
                               [](const OdomRecord& o, double t) { return o.stamp_s < t; });
    if (it == odo.begin() || it == odo.end()) continue;
    const OdomRecord &b = *it, &a = *(it - 1);
    const double span = b.stamp_s - a.stamp_s;
    if (span <= 0 || span > 1.0) continue;  // a gap in the odometry: keep the logged pose
    const double f = (taken_s - a.stamp_s) / span;
    const core::Pose2 step = core::Between(a.pose, b.pose);
    r.odom_pose = a.pose * core::Pose2(f * step.x_m, f * step.y_m, f * step.theta_rad);
    ++done;
  }
  return done;
}

core::Result<CarmenLog> ReadCarmenLog(const std::string& path, const CarmenReadOptions& options) {
  std::ifstream in(path);
  if (!in) return core::NotFound(path + ": cannot open");
  CarmenLog log;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') {
      ++log.skipped_lines;
      continue;
    }
    FLEETMAP_RETURN_IF_ERROR(ParseCarmenLine(line, n, options, log).WithContext(path));
  }
  if (log.lasers.empty()) return core::InvalidArgument(path + ": no FLASER or ROBOTLASER1 lines");
  return log;
}

}  // namespace fleetmap::eval::carmen
