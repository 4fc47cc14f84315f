#include "eval/carmen/relation_audit.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace fleetmap::eval::carmen {
namespace {

// The points of one scan bucketed in square cells of the gate's size: a nearest neighbour
// within the gate is in the query's cell or one of its eight neighbours.
class PointBuckets {
 public:
  PointBuckets(const std::vector<Eigen::Vector2d>& points, double cell_m) : cell_m_(cell_m) {
    for (const Eigen::Vector2d& p : points) buckets_[Key(Cell(p.x()), Cell(p.y()))].push_back(p);
  }

  double NearestWithin(const Eigen::Vector2d& q, double gate_m) const {
    double best = gate_m;
    const int64_t cx = Cell(q.x()), cy = Cell(q.y());
    for (int64_t x = cx - 1; x <= cx + 1; ++x) {
      for (int64_t y = cy - 1; y <= cy + 1; ++y) {
        const auto it = buckets_.find(Key(x, y));
        if (it == buckets_.end()) continue;
        for (const Eigen::Vector2d& p : it->second) best = std::min(best, (p - q).norm());
      }
    }
    return best;
  }

 private:
  int64_t Cell(double v) const { return static_cast<int64_t>(std::floor(v / cell_m_)); }
  static int64_t Key(int64_t x, int64_t y) { return x * 1000003 + y; }
  double cell_m_;
  std::unordered_map<int64_t, std::vector<Eigen::Vector2d>> buckets_;
};

// ScanFit with `first` already bucketed (a relation scores two poses against the same scan).
double MeanNearest(const PointBuckets& first, const std::vector<Eigen::Vector2d>& second,
                   const core::Pose2& second_in_first, double gate_m) {
  if (second.empty()) return gate_m;
  double sum = 0.0;
  for (const Eigen::Vector2d& p : second) {
    sum += first.NearestWithin(second_in_first.Apply(p), gate_m);
  }
  return sum / second.size();
}

bool IsLatticeLength(double length_m, double step_m, double tolerance_m) {
  constexpr int kSteps = 20;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= i; ++j) {
      if (i == 0 && j == 0) continue;
      if (std::abs(length_m - step_m * std::hypot(i, j)) <= tolerance_m) return true;
    }
  }
  return false;
}

}  // namespace

LatticeCheck CheckLattice(const std::vector<Relation>& relations,
                          const std::vector<TimedPose>& odometry, double step_m, double tolerance_m,
                          double max_span_s) {
  LatticeCheck check;
  for (const Relation& r : relations) {
    if (std::abs(r.t2_s - r.t1_s) > max_span_s) continue;
    const TimedPose *a = NearestInTime(odometry, r.t1_s), *b = NearestInTime(odometry, r.t2_s);
    if (!a || !b) continue;
    ++check.relations;
    const core::Pose2 odom = core::Between(a->pose, b->pose);
    const double difference_m = std::hypot(r.delta.x_m - odom.x_m, r.delta.y_m - odom.y_m);
    if (difference_m <= tolerance_m) {
      ++check.equal_to_odometry;
    } else if (IsLatticeLength(difference_m, step_m, tolerance_m)) {
      ++check.on_lattice;
    }
  }
  return check;
}

std::vector<Eigen::Vector2d> EndPointsInBase(const LaserRecord& record,
                                             const ScanFitOptions& options) {
  std::vector<Eigen::Vector2d> points;
  const core::LaserScan& scan = record.scan;
  for (size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double r = scan.ranges_m[i];
    // NaN fails both comparisons; "no return" is at or above range_max_m.
    if (!(r >= options.min_range_m && r <= options.max_range_m && r < scan.range_max_m)) continue;
    const double a = scan.angle(i);
    points.push_back(record.laser_in_base.Apply({r * std::cos(a), r * std::sin(a)}));
  }
  return points;
}

double ScanFit(const std::vector<Eigen::Vector2d>& first,
               const std::vector<Eigen::Vector2d>& second, const core::Pose2& second_in_first,
               double gate_m) {
  return MeanNearest(PointBuckets(first, gate_m), second, second_in_first, gate_m);
}

FitComparison CompareScanFit(const std::vector<Relation>& relations, const CarmenLog& log,
                             const std::vector<TimedPose>& estimate, const ScanFitOptions& options,
                             double max_span_s) {
  // The scans as a trajectory, to find them by time as the score does.
  std::vector<TimedPose> scans;
  scans.reserve(log.lasers.size());
  for (const LaserRecord& r : log.lasers) scans.push_back({r.stamp_s, r.odom_pose});
  FitComparison out;
  for (const Relation& r : relations) {
    if (std::abs(r.t2_s - r.t1_s) > max_span_s) continue;
    const TimedPose *s1 = NearestInTime(scans, r.t1_s), *s2 = NearestInTime(scans, r.t2_s);
    const TimedPose *e1 = NearestInTime(estimate, r.t1_s), *e2 = NearestInTime(estimate, r.t2_s);
    if (!s1 || !s2 || !e1 || !e2) continue;
    const auto first = EndPointsInBase(log.lasers[s1 - scans.data()], options);
    const auto second = EndPointsInBase(log.lasers[s2 - scans.data()], options);
    const core::Pose2 estimated = core::Between(e1->pose, e2->pose);
    const PointBuckets first_buckets(first, options.gate_m);
    const double by_reference = MeanNearest(first_buckets, second, r.delta, options.gate_m);
    const double by_estimate = MeanNearest(first_buckets, second, estimated, options.gate_m);
    ++out.relations;
    out.reference_fit_m += by_reference;
    out.estimate_fit_m += by_estimate;
    out.estimate_error_m += std::hypot(estimated.x_m - r.delta.x_m, estimated.y_m - r.delta.y_m);
    if (by_estimate < by_reference - 1e-4) ++out.estimate_better;
    if (by_reference < by_estimate - 1e-4) ++out.reference_better;
  }
  if (out.relations > 0) {
    out.reference_fit_m /= out.relations;
    out.estimate_fit_m /= out.relations;
    out.estimate_error_m /= out.relations;
  }
  return out;
}

}  // namespace fleetmap::eval::carmen
