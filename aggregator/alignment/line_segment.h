// A line segment and its Hesse normal form, the paper's line feature (Sec. 3.4): the normal
// distance r from the frame's origin and the angle theta of the normal against the x axis.
// Lines are undirected, so theta is kept in [0, pi) and r carries the sign.
#pragma once

#include <Eigen/Core>

#include "core/pose2.h"

namespace fleetmap::aggregator {

struct HesseLine {
  double r = 0.0;          // signed normal distance of the line from the frame's origin
  double theta_rad = 0.0;  // angle of the normal, [0, pi)
};

struct LineSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  // end points, in the units of the frame
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  // The edge's facing is known: a -> b runs with the free side on its left. The two faces of
  // a thin wall, or a wall and the pallet in front of it, then never match each other.
  bool oriented = false;

  double length() const { return (b - a).norm(); }
  Eigen::Vector2d midpoint() const { return 0.5 * (a + b); }
  // Unit vector from a to b ((1, 0) for a degenerate segment).
  Eigen::Vector2d direction() const;
  // The unit normal of the Hesse form: (cos theta, sin theta).
  Eigen::Vector2d normal() const;
  HesseLine hesse() const;
  // Signed distance of `p` from the infinite line, along normal().
  double SignedDistance(const Eigen::Vector2d& p) const { return normal().dot(p - a); }
  // Position of p's foot on the line, measured from a along direction().
  double Along(const Eigen::Vector2d& p) const { return direction().dot(p - a); }
  // The segment with both end points mapped by `pose` (pose * point).
  LineSegment Transformed(const core::Pose2& pose) const;
  LineSegment Scaled(double factor) const { return {a * factor, b * factor, oriented}; }
  // Both oriented and facing opposite ways (their directions more than 90 degrees apart).
  bool FacesAwayFrom(const LineSegment& o) const {
    return oriented && o.oriented && (b - a).dot(o.b - o.a) < 0;
  }
};

// Angle of an undirected line's direction, [0, pi).
double LineDirectionAngle(const Eigen::Vector2d& direction);
// How far a line of direction angle `to_rad` is turned from one of `from_rad`, for undirected
// lines: wrapped into [-pi/2, pi/2).
double LineAngleDiff(double from_rad, double to_rad);

}  // namespace fleetmap::aggregator
