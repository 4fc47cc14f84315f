// Reader of CARMEN text logs, the format of the classic SLAM benchmark datasets (intel, aces,
// fr079 ...): FLASER, ROBOTLASER1 and ODOM lines. Other message types are skipped and
// counted; malformed lines are errors naming the line number.
#pragma once

#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/scan.h"

namespace fleetmap::eval::carmen {

struct LaserRecord {
  double stamp_s = 0.0;  // ipc_timestamp
  core::LaserScan scan;
  core::Pose2 odom_pose;      // the robot's odometry pose at the scan
  core::Pose2 laser_in_base;  // ROBOTLASER1: laser pose relative to the robot; FLASER: identity
};

struct OdomRecord {
  double stamp_s = 0.0;
  core::Pose2 pose;
  double v_mps = 0.0, omega_radps = 0.0;
};

struct CarmenLog {
  std::vector<LaserRecord> lasers;  // in file order
  std::vector<OdomRecord> odometry;
  int skipped_lines = 0;  // comments and message types we do not read
};

struct CarmenReadOptions {
  // FLASER lines carry no range limit: returns at or above this are treated as no return.
  double flaser_max_range_m = 50.0;
  int64_t max_file_bytes = int64_t{1} << 31;
};

// Replaces each laser record's odometry pose by the ODOM lines interpolated at the scan's time
// stamp: the pose embedded in FLASER lines is the last ODOM before the scan, up to one odometry
// period stale. `scan_latency_s`: how long before its time stamp a scan was taken (a scan stamped
// on arrival is late by its transmission: ~0.2 s for a 361-beam scan over 38400-baud serial);
// the odometry is read at stamp - latency. Scans outside the ODOM lines' time span keep their
// pose. Returns how many records were interpolated.
int InterpolateOdometryAtScans(CarmenLog& log, double scan_latency_s = 0.0);

core::Result<CarmenLog> ReadCarmenLog(const std::string& path,
                                      const CarmenReadOptions& options = {});
// One line; `line_number` only for messages. Returns true when the line held a laser.
core::Status ParseCarmenLine(const std::string& line, int line_number,
                             const CarmenReadOptions& options, CarmenLog& log);

}  // namespace fleetmap::eval::carmen
