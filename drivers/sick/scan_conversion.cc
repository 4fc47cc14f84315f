#include "drivers/sick/scan_conversion.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fleetmap::drivers::sick {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

core::Status ScanConversionOptions::Validate() const {
  if (range_channel.size() != 5) {
    return core::InvalidArgument("scan_conversion.range_channel must have 5 characters");
  }
  if (!(range_min_m >= 0.0)) return core::InvalidArgument("scan_conversion.range_min_m < 0");
  if (!(range_max_m > range_min_m)) {
    return core::InvalidArgument("scan_conversion.range_max_m must exceed range_min_m");
  }
  if (!std::isfinite(angle_offset_rad)) {
    return core::InvalidArgument("scan_conversion.angle_offset_rad must be finite");
  }
  return core::OkStatus();
}

core::Result<core::LaserScan> ToLaserScan(const ScanTelegram& telegram,
                                          const ScanConversionOptions& options, double stamp_s) {
  const ScanChannel* ranges = telegram.FindChannel(options.range_channel);
  if (ranges == nullptr) {
    return core::InvalidArgument("scan has no channel " + options.range_channel);
  }
  if (ranges->values.empty() || ranges->angular_step_1e4deg == 0) {
    return core::InvalidArgument("channel " + ranges->content + " is empty or has no step");
  }
  core::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.angle_min_rad = ranges->start_angle_deg() * kDegToRad + options.angle_offset_rad;
  scan.angle_increment_rad = ranges->angular_step_deg() * kDegToRad;
  scan.range_min_m = options.range_min_m;
  scan.range_max_m = options.range_max_m;
  const double hz = telegram.scan_frequency_hz();
  scan.scan_period_s = hz > 0.0 ? 1.0 / hz : 0.0;
  scan.ranges_m.resize(ranges->values.size());
  for (size_t i = 0; i < ranges->values.size(); ++i) {
    scan.ranges_m[i] = ranges->values[i] == 0 ? std::numeric_limits<float>::infinity()
                                              : static_cast<float>(ranges->Scaled(i) * 1e-3);
  }
  const ScanChannel* rssi =
      options.intensity_channel.empty() ? nullptr : telegram.FindChannel(options.intensity_channel);
  if (rssi != nullptr && rssi->values.size() == ranges->values.size()) {
    scan.intensities.resize(rssi->values.size());
    for (size_t i = 0; i < rssi->values.size(); ++i) {
      scan.intensities[i] = static_cast<float>(rssi->Scaled(i));
    }
  }
  return scan;
}

}  // namespace fleetmap::drivers::sick

namespace fleetmap::drivers::sick {

ScanTelegram FromLaserScan(const core::LaserScan& scan, double angle_offset_rad) {
  ScanTelegram t;
  if (scan.scan_period_s > 0) {
    t.scan_frequency_centihz = static_cast<uint32_t>(std::lround(100.0 / scan.scan_period_s));
  }
  ScanChannel dist;
  dist.content = "DIST1";
  dist.start_angle_1e4deg =
      static_cast<int32_t>(std::lround((scan.angle_min_rad - angle_offset_rad) / kDegToRad * 1e4));
  dist.angular_step_1e4deg =
      static_cast<uint16_t>(std::lround(std::abs(scan.angle_increment_rad) / kDegToRad * 1e4));
  dist.scale_factor = scan.range_max_m > 65.5 ? 2.0f : 1.0f;
  dist.values.resize(scan.size());
  for (size_t i = 0; i < scan.size(); ++i) {
    const double mm = scan.IsValidReturn(i) ? scan.ranges_m[i] * 1e3 / dist.scale_factor : 0.0;
    dist.values[i] = static_cast<uint16_t>(std::clamp(std::lround(mm), 0L, 65535L));
  }
  ScanChannel rssi = dist;
  t.channels16.push_back(std::move(dist));
  if (scan.intensities.size() == scan.size()) {
    rssi.content = "RSSI1";
    rssi.scale_factor = 1.0f;
    for (size_t i = 0; i < scan.size(); ++i) {
      rssi.values[i] =
          static_cast<uint16_t>(std::clamp(std::lround(scan.intensities[i]), 0L, 65535L));
    }
    t.channels16.push_back(std::move(rssi));
  }
  return t;
}

}  // namespace fleetmap::drivers::sick
