// How far a vehicle's temporary-map builder drifted while it built one map: its poses in the
// map's frame against the true motion since the map's first pose. The aggregator can place a
// map no better than the map agrees with itself, so this bounds the alignment from below
// (docs/evaluation.md).
#pragma once

#include <functional>
#include <vector>

#include "core/map/temp_map.h"
#include "core/pose2.h"

namespace fleetmap::eval {

struct TempMapDrift {
  // The largest error over the map's poses, NaN for a map without poses.
  double translation_m = 0.0;
  double rotation_deg = 0.0;
};

// `truth_at(t)` is the vehicle's true pose at time t (any fixed frame).
TempMapDrift BuilderDrift(const std::vector<core::TimedPose>& trajectory_in_temp,
                          const std::function<core::Pose2(double)>& truth_at);

}  // namespace fleetmap::eval
