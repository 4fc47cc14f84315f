// The other side of diff_drive_odometry.h: turns a differential-drive vehicle's odometry into
// the frames its drive nodes would send (a SYNC and the two TPDOs per sample), so that the
// simulator's vehicles can be written as a candump log and replayed onto a real bus.
// Wheel positions are accumulated exactly and rounded once, so no rounding error builds up.
#pragma once

#include <optional>
#include <vector>

#include "core/odometry.h"
#include "drivers/can/can_frame.h"
#include "drivers/can/diff_drive_can_options.h"

namespace fleetmap::drivers::can {

class DiffDriveCanEncoder {
 public:
  // `start_ticks` is the encoder position of both wheels at the first sample (position
  // mapping), e.g. near INT32_MAX to exercise the wrap-around.
  explicit DiffDriveCanEncoder(DiffDriveCanOptions options, int64_t start_ticks = 0);

  // SYNC at sample.stamp_s, then left and right TPDO 0.2 and 0.4 ms later.
  std::vector<CanFrame> Encode(const core::OdometrySample& sample);

 private:
  CanFrame Pdo(const DriveNodeOptions& node, double value, double stamp_s) const;

  const DiffDriveCanOptions options_;
  std::optional<core::Pose2> previous_;
  double ticks_[2];  // accumulated encoder ticks, left and right, unrounded
};

}  // namespace fleetmap::drivers::can
