// From an LMDscandata telegram to a core::LaserScan in the scanner frame used everywhere else
// (x ahead, y left, angles counter-clockwise from x). SICK counts angles from the scanner's
// right, so 90 degrees in a telegram is straight ahead: angle = sick_angle - 90 degrees. A
// TiM781S scan starting at -45 degrees therefore starts at -135 degrees here.
#pragma once

#include <string>

#include "core/result.h"
#include "core/scan.h"
#include "drivers/sick/scan_telegram.h"

namespace fleetmap::drivers::sick {

struct ScanConversionOptions {
  std::string range_channel = "DIST1";      // the channel that holds distances (mm after scaling)
  std::string intensity_channel = "RSSI1";  // remission; empty or absent: no intensities
  double range_min_m = 0.05;                // closer returns are invalid (data sheets: 0.05 m)
  double range_max_m = 80.0;                // LMS511 reach; TiM781S 25 m, LMS111 20 m
  // Added to every SICK angle to get the scanner-frame angle, radians (-pi/2, see above).
  double angle_offset_rad = -1.5707963267948966;
  core::Status Validate() const;
};

// A raw distance of 0 means no echo and becomes +infinity. `stamp_s` is the host time of the
// first beam (device_clock.h maps the telegram's device time).
core::Result<core::LaserScan> ToLaserScan(const ScanTelegram& telegram,
                                          const ScanConversionOptions& options, double stamp_s);

}  // namespace fleetmap::drivers::sick

namespace fleetmap::drivers::sick {

// The inverse, for emulators and tests: a telegram whose DIST1 (mm, scale 1; scale 2 when
// ranges exceed 65.5 m) and, if the scan has intensities, RSSI1 reproduce `scan`. Invalid
// returns (not finite, outside the limits) become 0, "no echo". Header fields are left at
// their defaults for the caller to fill in (counters, device times, frequency).
ScanTelegram FromLaserScan(const core::LaserScan& scan,
                           double angle_offset_rad = -1.5707963267948966);

}  // namespace fleetmap::drivers::sick
