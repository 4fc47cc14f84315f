#include "vehicle_agent/node/can_odometry_input.h"

namespace fleetmap::vehicle_agent::node {

core::Status CanInputOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(socket.Validate().WithContext("inputs.can"));
  return odometry.Validate().WithContext("inputs.can.mapping");
}

std::vector<drivers::can::CanIdFilter> OdometryFilters(const drivers::can::DiffDriveCanOptions& o) {
  constexpr uint32_t kStandardMask = 0x7FF;
  return {{o.sync_cob_id, kStandardMask, false},
          {o.left.cob_id(), kStandardMask, false},
          {o.right.cob_id(), kStandardMask, false}};
}

core::Result<std::unique_ptr<CanOdometryInput>> CanOdometryInput::Open(
    const CanInputOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  drivers::can::SocketCanOptions socket = options.socket;
  socket.filters = OdometryFilters(options.odometry);
  core::Result<drivers::can::SocketCan> opened = drivers::can::SocketCan::Open(socket);
  if (!opened.ok()) return opened.status().WithContext("CAN interface " + socket.interface);
  return std::unique_ptr<CanOdometryInput>(
      new CanOdometryInput(std::move(opened).value(), options.odometry));
}

std::vector<core::OdometrySample> CanOdometryInput::Drain() {
  std::vector<core::OdometrySample> samples;
  frames_.clear();
  if (!socket_.ReadAvailable(frames_).ok()) {
    ++read_errors_;  // the socket keeps its queue: the next pass tries again
    return samples;
  }
  for (const drivers::can::CanFrame& frame : frames_) {
    if (std::optional<core::OdometrySample> s = odometry_.Decode(frame)) samples.push_back(*s);
  }
  return samples;
}

NamedCounters CanOdometryInput::Counters() const {
  const drivers::can::SocketCanStats& s = socket_.stats();
  const drivers::can::CanOdometryStats& o = odometry_.stats();
  const auto n = [](uint64_t v) { return static_cast<int64_t>(v); };
  return {
      {"can_frames", n(s.frames)},
      {"can_kernel_drops", n(s.kernel_drops)},
      {"can_error_frames", n(s.error_frames)},
      {"can_read_errors", read_errors_},
      {"can_odometry_samples", n(o.samples)},
      {"can_incomplete_cycles", n(o.incomplete_cycles)},
      {"can_bad_frames", n(o.wrong_dlc + o.unknown_nodes + o.out_of_cycle)},
  };
}

}  // namespace fleetmap::vehicle_agent::node
