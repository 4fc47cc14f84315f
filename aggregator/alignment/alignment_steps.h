// Small pieces both alignment modes are built from: moving segments and points by a pose,
// a rotation about a point, and the weighted estimates (the paper's mean, our robust one).
#pragma once

#include <vector>

#include "aggregator/alignment/line_segment.h"
#include "core/pose2.h"

namespace fleetmap::aggregator {

std::vector<LineSegment> PlaceSegments(const std::vector<LineSegment>& segments,
                                       const core::Pose2& pose);
std::vector<Eigen::Vector2d> PlacePoints(const std::vector<Eigen::Vector2d>& points,
                                         const core::Pose2& pose);

// The rigid motion that turns by `angle_rad` about `pivot` (both in the same frame).
core::Pose2 RotationAbout(const Eigen::Vector2d& pivot, double angle_rad);
// A pure translation.
inline core::Pose2 Translation(const Eigen::Vector2d& t) { return {t.x(), t.y(), 0.0}; }

struct Weighted {
  double value = 0.0;
  double weight = 0.0;
};
// The weighted median (the lower one on a tie); 0 for no samples.
double WeightedMedian(std::vector<Weighted> samples);
// The weighted mean of the samples within `inlier` of the weighted median.
double RobustWeightedMean(const std::vector<Weighted>& samples, double inlier);
// The length-weighted mean, without outlier rejection (the paper's estimate).
double WeightedMean(const std::vector<Weighted>& samples);

}  // namespace fleetmap::aggregator
