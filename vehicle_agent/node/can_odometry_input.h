// Wheel odometry from a CANopen differential drive over SocketCAN (drivers/can): the SYNC and
// the two drives' TPDOs are let through the socket's filters, every completed SYNC cycle is
// one odometry sample stamped with the kernel's receive time of the SYNC (CLOCK_REALTIME, the
// clock scans are stamped in). Never blocks: the loop drains it every pass.
#pragma once

#include <memory>
#include <vector>

#include "drivers/can/diff_drive_odometry.h"
#include "drivers/can/socketcan.h"
#include "vehicle_agent/node/agent_counters.h"

namespace fleetmap::vehicle_agent::node {

struct CanInputOptions {
  drivers::can::SocketCanOptions socket;       // interface (filters are set here)
  drivers::can::DiffDriveCanOptions odometry;  // the CANopen mapping (docs/drivers.md)
  core::Status Validate() const;
};

class CanOdometryInput {
 public:
  // Opens the interface: NotFound for an unknown one, Unimplemented without AF_CAN.
  static core::Result<std::unique_ptr<CanOdometryInput>> Open(const CanInputOptions& options);

  // Every sample completed by the frames queued now.
  std::vector<core::OdometrySample> Drain();

  // can_frames, can_kernel_drops, can_error_frames, can_odometry_samples,
  // can_incomplete_cycles, can_bad_frames (wrong length, unknown node, out of cycle).
  NamedCounters Counters() const;

 private:
  CanOdometryInput(drivers::can::SocketCan socket, const drivers::can::DiffDriveCanOptions& o)
      : socket_(std::move(socket)), odometry_(o) {}

  drivers::can::SocketCan socket_;
  drivers::can::DiffDriveOdometry odometry_;
  std::vector<drivers::can::CanFrame> frames_;  // scratch
  int64_t read_errors_ = 0;
};

// The SocketCAN filters that let exactly SYNC and the two drives' TPDOs through.
std::vector<drivers::can::CanIdFilter> OdometryFilters(const drivers::can::DiffDriveCanOptions& o);

}  // namespace fleetmap::vehicle_agent::node
