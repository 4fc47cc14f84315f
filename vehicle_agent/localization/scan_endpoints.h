// Turns a laser scan into the beam end points the particle filter scores: up to `max_beams`
// usable returns, spread evenly over the scan, in the vehicle (base) frame.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/pose2.h"
#include "core/scan.h"

namespace fleetmap::vehicle_agent {

struct EndpointCounts {
  int returns = 0;    // usable returns in the whole scan
  int invalid = 0;    // NaN, -inf, zero, negative or below range_min_m
  int no_return = 0;  // +inf or at/above min(range_max_m, max_range_m)
};

// Fills `endpoints_in_base` (cleared first) with the end points of at most `max_beams` returns
// (every usable return when there are fewer). `scanner_in_base` must be finite.
EndpointCounts ScanEndpoints(const core::LaserScan& scan, const core::Pose2& scanner_in_base,
                             int max_beams, double max_range_m,
                             std::vector<Eigen::Vector2f>& endpoints_in_base);

}  // namespace fleetmap::vehicle_agent
