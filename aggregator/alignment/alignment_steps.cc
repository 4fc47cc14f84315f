#include "aggregator/alignment/alignment_steps.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::aggregator {

std::vector<LineSegment> PlaceSegments(const std::vector<LineSegment>& segments,
                                       const core::Pose2& pose) {
  std::vector<LineSegment> placed;
  placed.reserve(segments.size());
  for (const LineSegment& s : segments) placed.push_back(s.Transformed(pose));
  return placed;
}

std::vector<Eigen::Vector2d> PlacePoints(const std::vector<Eigen::Vector2d>& points,
                                         const core::Pose2& pose) {
  const double c = std::cos(pose.theta_rad), s = std::sin(pose.theta_rad);
  std::vector<Eigen::Vector2d> placed;
  placed.reserve(points.size());
  for (const Eigen::Vector2d& p : points)
    placed.emplace_back(pose.x_m + c * p.x() - s * p.y(), pose.y_m + s * p.x() + c * p.y());
  return placed;
}

core::Pose2 RotationAbout(const Eigen::Vector2d& pivot, double angle_rad) {
  const core::Pose2 turn(0.0, 0.0, angle_rad);
  const Eigen::Vector2d t = pivot - turn.Apply(pivot);
  return {t.x(), t.y(), angle_rad};
}

double WeightedMedian(std::vector<Weighted> samples) {
  if (samples.empty()) return 0.0;
  std::stable_sort(samples.begin(), samples.end(),
                   [](const Weighted& a, const Weighted& b) { return a.value < b.value; });
  double total = 0.0;
  for (const Weighted& s : samples) total += s.weight;
  double running = 0.0;
  for (const Weighted& s : samples) {
    running += s.weight;
    if (running >= 0.5 * total) return s.value;
  }
  return samples.back().value;
}

double WeightedMean(const std::vector<Weighted>& samples) {
  double sum = 0.0, weight = 0.0;
  for (const Weighted& s : samples) {
    sum += s.value * s.weight;
    weight += s.weight;
  }
  return weight > 0 ? sum / weight : 0.0;
}

double RobustWeightedMean(const std::vector<Weighted>& samples, double inlier) {
  const double median = WeightedMedian(samples);
  std::vector<Weighted> inliers;
  for (const Weighted& s : samples)
    if (std::abs(s.value - median) <= inlier) inliers.push_back(s);
  return inliers.empty() ? median : WeightedMean(inliers);
}

}  // namespace fleetmap::aggregator
