#include "eval/carmen/relations.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>

#include "core/io/file_io.h"

namespace fleetmap::eval::carmen {
namespace {

void MeanStd(const std::vector<double>& v, double& mean, double& std) {
  mean = std = 0.0;
  if (v.empty()) return;
  for (double x : v) mean += x;
  mean /= v.size();
  for (double x : v) std += (x - mean) * (x - mean);
  std = std::sqrt(std / v.size());
}

}  // namespace

// Nearest, not the first within 1 ms: intel's scans come in bursts, two of them 1.0-1.3 ms
// apart, and the earlier one is a scan period of motion away from the one the relation names.
const TimedPose* NearestInTime(const std::vector<TimedPose>& trajectory, double t) {
  constexpr double kTolerance_s = 1e-3;
  auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                             [](const TimedPose& p, double v) { return p.stamp_s < v; });
  if (it != trajectory.begin() &&
      (it == trajectory.end() || t - std::prev(it)->stamp_s < it->stamp_s - t)) {
    --it;
  }
  if (it == trajectory.end() || std::abs(it->stamp_s - t) > kTolerance_s) return nullptr;
  return &*it;
}

core::Result<std::vector<Relation>> ReadRelations(const std::string& path) {
  std::ifstream in(path);
  if (!in) return core::NotFound(path + ": cannot open");
  std::vector<Relation> relations;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream f(line);
    double t1, t2, x, y, z, roll, pitch, yaw;
    if (!(f >> t1 >> t2 >> x >> y >> z >> roll >> pitch >> yaw) ||
        !std::isfinite(t1 + t2 + x + y + yaw)) {
      return core::InvalidArgument(path + ": line " + std::to_string(n) + ": malformed relation");
    }
    relations.push_back({t1, t2, core::Pose2(x, y, yaw)});
  }
  return relations;
}

core::Result<std::vector<TimedPose>> ReadTrajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) return core::NotFound(path + ": cannot open");
  std::vector<TimedPose> trajectory;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream f(line);
    TimedPose p;
    if (!(f >> p.stamp_s >> p.pose.x_m >> p.pose.y_m >> p.pose.theta_rad) ||
        !std::isfinite(p.stamp_s + p.pose.x_m + p.pose.y_m + p.pose.theta_rad))
      return core::InvalidArgument(path + ": line " + std::to_string(n) + ": not `t x y theta`");
    trajectory.push_back(p);
  }
  std::stable_sort(trajectory.begin(), trajectory.end(),
                   [](const TimedPose& a, const TimedPose& b) { return a.stamp_s < b.stamp_s; });
  return trajectory;
}

core::Status WriteTrajectory(const std::string& path, const std::vector<TimedPose>& trajectory) {
  std::ostringstream text;
  text << "# t x y theta (s, m, m, rad)\n" << std::fixed << std::setprecision(6);
  for (const TimedPose& p : trajectory) {
    text << p.stamp_s << ' ' << p.pose.x_m << ' ' << p.pose.y_m << ' ' << p.pose.theta_rad << '\n';
  }
  return core::WriteFileAtomically(path, text.str());
}

RelationErrors ScoreRelations(const std::vector<Relation>& relations,
                              const std::vector<TimedPose>& trajectory, double max_span_s) {
  RelationErrors e;
  std::vector<double> trans, rot;
  for (const Relation& r : relations) {
    if (std::abs(r.t2_s - r.t1_s) > max_span_s) continue;
    const TimedPose *a = NearestInTime(trajectory, r.t1_s), *b = NearestInTime(trajectory, r.t2_s);
    if (!a || !b) {
      ++e.missing;
      continue;
    }
    const core::Pose2 error = core::Between(r.delta, core::Between(a->pose, b->pose));
    trans.push_back(std::hypot(error.x_m, error.y_m));
    rot.push_back(std::abs(error.theta_rad) * 180.0 / M_PI);
  }
  e.used = static_cast<int>(trans.size());
  MeanStd(trans, e.trans_mean_m, e.trans_std_m);
  MeanStd(rot, e.rot_mean_deg, e.rot_std_deg);
  return e;
}

double RelationErrors::missing_share() const {
  const int in_span = used + missing;
  return in_span > 0 ? static_cast<double>(missing) / in_span
                     : std::numeric_limits<double>::quiet_NaN();
}

core::Status CheckScored(const RelationErrors& errors, const std::vector<Relation>& relations,
                         const std::vector<TimedPose>& trajectory, double max_span_s) {
  if (errors.used > 0) return core::OkStatus();
  std::ostringstream why;
  why << std::fixed << std::setprecision(3) << "no relation scored: " << relations.size()
      << " relations";
  if (std::isfinite(max_span_s)) {
    why << ", " << errors.missing << " of them spanning at most " << max_span_s << " s";
  }
  why << ", none with both time stamps in the trajectory (within 1 ms)";
  if (!relations.empty()) {
    double lo = relations.front().t1_s, hi = lo;
    for (const Relation& r : relations) {
      lo = std::min({lo, r.t1_s, r.t2_s});
      hi = std::max({hi, r.t1_s, r.t2_s});
    }
    why << "; relations from " << lo << " to " << hi << " s";
  }
  if (trajectory.empty()) {
    why << "; the trajectory is empty";
  } else {
    why << "; trajectory from " << trajectory.front().stamp_s << " to " << trajectory.back().stamp_s
        << " s (" << trajectory.size() << " poses)";
  }
  return core::NotFound(why.str());
}

}  // namespace fleetmap::eval::carmen
