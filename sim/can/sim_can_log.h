// The simulator's vehicles as CAN buses: runs a World, takes one vehicle's odometry and
// encodes it as its CANopen drive nodes would send it (drivers/can/diff_drive_can_encoder.h),
// ready to be written as a candump log and replayed with canplayer. The odometry samples are
// returned too, so that a test can compare what a decoder recovers with what was sent.
#pragma once

#include <string>
#include <vector>

#include "core/odometry.h"
#include "core/result.h"
#include "drivers/can/candump_log.h"
#include "drivers/can/diff_drive_can_options.h"
#include "sim/world.h"

namespace fleetmap::sim::can {

struct SimCanLogOptions {
  size_t vehicle = 0;              // index into the scenario's vehicles
  double duration_s = 0.0;         // 0: the whole scenario
  std::string interface = "can0";  // written into every record
  double start_time_s = 1.7e9;     // log time of simulation time 0 (epoch seconds)
  int64_t start_ticks = 0;         // encoder position at the start (wrap-around tests)
  drivers::can::DiffDriveCanOptions can;
  core::Status Validate() const;
};

struct SimCanLog {
  std::vector<drivers::can::CandumpRecord> records;
  std::vector<core::OdometrySample> odometry;  // the simulator's odometry, log-time stamps
};

core::Result<SimCanLog> RecordOdometryAsCan(const sim::World& world,
                                            const SimCanLogOptions& options);

}  // namespace fleetmap::sim::can
