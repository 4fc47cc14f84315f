// The emulator's S300 side: scans as the continuous data output of an S300 safety scanner
// (drivers/sick/s300_telegram.h), written to a file descriptor (a serial port, a
// pseudo-terminal, a file).
#pragma once

#include <cstddef>

#include "core/result.h"
#include "core/scan.h"
#include "drivers/sick/s300_telegram.h"
#include "sim/sick/scan_source.h"

namespace fleetmap::sim::sick {

// Ranges in cm (13 bits; beyond 81.91 m or invalid: 0), `beams` resampled evenly from the scan.
drivers::sick::S300Telegram S300FromLaserScan(const core::LaserScan& scan, uint32_t scan_number,
                                              size_t beams = 541);
// Writes `count` telegrams from `source` to `fd` (fewer if it runs out); returns how many.
core::Result<size_t> WriteS300Stream(ScanSource& source, int fd, size_t count);

}  // namespace fleetmap::sim::sick
