#include "drivers/can/diff_drive_odometry.h"

#include <cassert>
#include <cmath>

namespace fleetmap::drivers::can {
namespace {

bool IsTpdoRange(uint32_t id) {
  const uint32_t function = id & 0x780;
  return (function == 0x180 || function == 0x280 || function == 0x380 || function == 0x480) &&
         (id & 0x7F) != 0;
}

}  // namespace

int32_t ReadLeInt32(const uint8_t* d, int offset) {
  const uint32_t v = uint32_t{d[offset]} | uint32_t{d[offset + 1]} << 8 |
                     uint32_t{d[offset + 2]} << 16 | uint32_t{d[offset + 3]} << 24;
  return static_cast<int32_t>(v);
}

DiffDriveOdometry::DiffDriveOdometry(DiffDriveCanOptions options) : options_(std::move(options)) {
  assert(options_.Validate().ok());
}

std::optional<core::OdometrySample> DiffDriveOdometry::Decode(const CanFrame& frame) {
  ++stats_.frames;
  if (frame.error) {
    ++stats_.error_frames;
    return std::nullopt;
  }
  if (frame.extended || frame.rtr || frame.fd) {
    ++stats_.other_frames;
    return std::nullopt;
  }
  if (frame.id == options_.sync_cob_id) {
    if (frame.len > 1) {
      ++stats_.wrong_dlc;
      return std::nullopt;
    }
    ++stats_.syncs;
    if (cycle_open_ && !(have_[0] && have_[1])) ++stats_.incomplete_cycles;
    cycle_open_ = true;
    cycle_stamp_s_ = frame.stamp_s;
    have_[0] = have_[1] = false;
    return std::nullopt;
  }
  if (frame.id == options_.left.cob_id()) return OnPdo(Side::kLeft, frame);
  if (frame.id == options_.right.cob_id()) return OnPdo(Side::kRight, frame);
  IsTpdoRange(frame.id) ? ++stats_.unknown_nodes : ++stats_.other_frames;
  return std::nullopt;
}

std::optional<core::OdometrySample> DiffDriveOdometry::OnPdo(Side side, const CanFrame& frame) {
  const int i = side == Side::kLeft ? 0 : 1;
  const DriveNodeOptions& node = i == 0 ? options_.left : options_.right;
  if (frame.len < node.byte_offset + 4) {
    ++stats_.wrong_dlc;
    return std::nullopt;
  }
  if (!cycle_open_ || have_[i]) {
    ++stats_.out_of_cycle;
    return std::nullopt;
  }
  ++stats_.pdos;
  raw_[i] = ReadLeInt32(frame.data.data(), node.byte_offset);
  have_[i] = true;
  if (!(have_[0] && have_[1])) return std::nullopt;
  cycle_open_ = false;
  return Integrate();
}

double DiffDriveOdometry::WheelMetres(const DriveNodeOptions& node, int32_t raw,
                                      int32_t previous) const {
  // Positions wrap around: the int32 difference is right across the wrap.
  const int32_t counts =
      node.object == DriveObject::kPosition
          ? static_cast<int32_t>(static_cast<uint32_t>(raw) - static_cast<uint32_t>(previous))
          : raw;
  const double metres = counts * node.scaling * options_.metres_per_tick();
  return node.inverted ? -metres : metres;
}

core::OdometrySample DiffDriveOdometry::Integrate() {
  core::OdometrySample sample;
  sample.stamp_s = cycle_stamp_s_;
  if (!initialized_) {
    initialized_ = true;
  } else {
    const double dt = cycle_stamp_s_ - previous_stamp_s_;
    double left = WheelMetres(options_.left, raw_[0], previous_raw_[0]);
    double right = WheelMetres(options_.right, raw_[1], previous_raw_[1]);
    if (options_.left.object == DriveObject::kVelocity) left *= dt;  // m/s over the cycle
    if (options_.right.object == DriveObject::kVelocity) right *= dt;
    const double ds = 0.5 * (left + right);
    const double dtheta = (right - left) / options_.track_width_m;
    const double heading = pose_.theta_rad + 0.5 * dtheta;
    pose_ = core::Pose2(pose_.x_m + ds * std::cos(heading), pose_.y_m + ds * std::sin(heading),
                        core::NormalizeAngle(pose_.theta_rad + dtheta));
    if (dt > 0.0) {
      sample.v_mps = ds / dt;
      sample.omega_radps = dtheta / dt;
    }
  }
  previous_raw_[0] = raw_[0];
  previous_raw_[1] = raw_[1];
  previous_stamp_s_ = cycle_stamp_s_;
  sample.pose_in_odom = pose_;
  ++stats_.samples;
  return sample;
}

}  // namespace fleetmap::drivers::can
