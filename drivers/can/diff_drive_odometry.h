// CANopen wheel odometry of a differential-drive AGV: every SYNC opens a cycle, the two drive
// nodes answer with synchronous TPDOs holding their encoder position (int32 ticks, wrapping
// around) or velocity, and once both arrived the cycle yields one odometry sample (x, y,
// theta, v, omega) stamped with the SYNC's receive time. Frames that do not fit (wrong DLC,
// unknown node, a cycle with a missing TPDO) are counted and skipped, never fatal.
#pragma once

#include <cstdint>
#include <optional>

#include "core/odometry.h"
#include "drivers/can/can_frame.h"
#include "drivers/can/diff_drive_can_options.h"

namespace fleetmap::drivers::can {

struct CanOdometryStats {
  uint64_t frames = 0;  // every frame decoded
  uint64_t syncs = 0;
  uint64_t pdos = 0;               // accepted TPDOs of the two drive nodes
  uint64_t samples = 0;            // odometry samples produced
  uint64_t wrong_dlc = 0;          // SYNC with more than 1 byte, TPDO too short for its mapping
  uint64_t unknown_nodes = 0;      // TPDOs (0x180..0x4FF) of nodes that are not our drives
  uint64_t incomplete_cycles = 0;  // a SYNC came before both TPDOs of the previous one
  uint64_t out_of_cycle = 0;       // TPDOs before the first SYNC or repeated within a cycle
  uint64_t error_frames = 0;
  uint64_t other_frames = 0;  // NMT, EMCY, heartbeat, extended ids, RTR
};

class DiffDriveOdometry {
 public:
  explicit DiffDriveOdometry(DiffDriveCanOptions options);

  // Feeds one received frame; returns a sample when it completes a SYNC cycle.
  std::optional<core::OdometrySample> Decode(const CanFrame& frame);

  const CanOdometryStats& stats() const { return stats_; }
  const core::Pose2& pose() const { return pose_; }
  const DiffDriveCanOptions& options() const { return options_; }

 private:
  enum class Side { kLeft, kRight };
  std::optional<core::OdometrySample> OnPdo(Side side, const CanFrame& frame);
  core::OdometrySample Integrate();
  // Wheel travel (m) or speed (m/s) of one side from its latest raw value.
  double WheelMetres(const DriveNodeOptions& node, int32_t raw, int32_t previous) const;

  const DiffDriveCanOptions options_;
  CanOdometryStats stats_;
  bool cycle_open_ = false;
  double cycle_stamp_s_ = 0.0;
  bool have_[2] = {false, false};
  int32_t raw_[2] = {0, 0};
  bool initialized_ = false;  // a first complete cycle gave the reference positions
  int32_t previous_raw_[2] = {0, 0};
  double previous_stamp_s_ = 0.0;
  core::Pose2 pose_;
};

// Reads the little-endian int32 at `offset` (the caller checked the length).
int32_t ReadLeInt32(const uint8_t* data, int offset);

}  // namespace fleetmap::drivers::can
