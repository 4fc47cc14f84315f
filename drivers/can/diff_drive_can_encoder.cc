#include "drivers/can/diff_drive_can_encoder.h"

#include <cassert>
#include <cmath>

namespace fleetmap::drivers::can {

DiffDriveCanEncoder::DiffDriveCanEncoder(DiffDriveCanOptions options, int64_t start_ticks)
    : options_(std::move(options)) {
  assert(options_.Validate().ok());
  ticks_[0] = ticks_[1] = static_cast<double>(start_ticks);
}

CanFrame DiffDriveCanEncoder::Pdo(const DriveNodeOptions& node, double value,
                                  double stamp_s) const {
  CanFrame f;
  f.id = node.cob_id();
  f.stamp_s = stamp_s;
  f.len = static_cast<uint8_t>(node.byte_offset + 4);
  // Raw counts wrap like a real int32 encoder register.
  const int64_t counts = std::llround(value / node.scaling) * (node.inverted ? -1 : 1);
  const uint32_t raw = static_cast<uint32_t>(static_cast<uint64_t>(counts));
  for (int b = 0; b < 4; ++b) f.data[node.byte_offset + b] = static_cast<uint8_t>(raw >> (8 * b));
  return f;
}

std::vector<CanFrame> DiffDriveCanEncoder::Encode(const core::OdometrySample& sample) {
  const double tick_m = options_.metres_per_tick();
  double value[2];
  const double half_track = 0.5 * options_.track_width_m;
  if (previous_) {
    const core::Pose2 step = core::Between(*previous_, sample.pose_in_odom);
    const double ds = std::copysign(std::hypot(step.x_m, step.y_m), step.x_m);
    ticks_[0] += (ds - step.theta_rad * half_track) / tick_m;
    ticks_[1] += (ds + step.theta_rad * half_track) / tick_m;
  }
  previous_ = sample.pose_in_odom;
  const DriveNodeOptions* nodes[2] = {&options_.left, &options_.right};
  for (int i = 0; i < 2; ++i) {
    const double wheel_speed = sample.v_mps + (i == 0 ? -1 : 1) * sample.omega_radps * half_track;
    value[i] = nodes[i]->object == DriveObject::kPosition ? ticks_[i] : wheel_speed / tick_m;
  }
  CanFrame sync;
  sync.id = options_.sync_cob_id;
  sync.stamp_s = sample.stamp_s;
  return {sync, Pdo(options_.left, value[0], sample.stamp_s + 0.0002),
          Pdo(options_.right, value[1], sample.stamp_s + 0.0004)};
}

}  // namespace fleetmap::drivers::can
