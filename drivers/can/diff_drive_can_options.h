// How a differential-drive AGV's two CANopen drive nodes report their wheels, loaded from
// YAML (docs/drivers.md lists every field):
//   sync_cob_id: 0x80            # SYNC; each SYNC makes both nodes send one TPDO
//   wheel_radius_m: 0.1
//   gear_ratio: 20               # motor turns per wheel turn
//   ticks_per_revolution: 4096   # encoder ticks per motor turn
//   track_width_m: 0.5
//   left:  {node_id: 1, object: position, tpdo_cob_id: 0x181, byte_offset: 0, scaling: 1.0}
//   right: {node_id: 2, object: position, inverted: true}
// `position`: the TPDO maps "position actual value" (0x6064, int32 encoder ticks, wrapping);
// `velocity`: "velocity actual value" (0x606C, int32 ticks per second).
#pragma once

#include <cstdint>
#include <string>

#include "core/result.h"

namespace fleetmap::drivers::can {

enum class DriveObject { kPosition, kVelocity };

struct DriveNodeOptions {
  int node_id = 1;           // CANopen node id, 1..127
  uint32_t tpdo_cob_id = 0;  // 0: TPDO1 default 0x180 + node_id
  DriveObject object = DriveObject::kPosition;
  int byte_offset = 0;    // where the int32 (little-endian) starts in the TPDO, 0..4
  double scaling = 1.0;   // raw * scaling = encoder ticks (or ticks/s); != 0
  bool inverted = false;  // mirrored motor: positive raw drives the wheel backwards
  uint32_t cob_id() const { return tpdo_cob_id != 0 ? tpdo_cob_id : 0x180u + node_id; }
};

struct DiffDriveCanOptions {
  uint32_t sync_cob_id = 0x80;           // 11-bit COB-ID of SYNC
  DriveNodeOptions left;                 // node 1 by default
  DriveNodeOptions right = Right();      // node 2 by default
  double wheel_radius_m = 0.1;           // > 0
  double gear_ratio = 1.0;               // motor turns per wheel turn, > 0
  double ticks_per_revolution = 4096.0;  // encoder ticks per motor turn, > 0
  double track_width_m = 0.5;            // distance between the wheels' contact points, > 0

  // Wheel travel per encoder tick.
  double metres_per_tick() const;
  core::Status Validate() const;

 private:
  static DriveNodeOptions Right() {
    DriveNodeOptions r;
    r.node_id = 2;
    return r;
  }
};

// Fields absent from the YAML keep their defaults; errors name the file, line and field.
core::Result<DiffDriveCanOptions> ParseDiffDriveCanOptions(const std::string& yaml_text,
                                                           const std::string& name);
core::Result<DiffDriveCanOptions> LoadDiffDriveCanOptions(const std::string& path);

}  // namespace fleetmap::drivers::can
