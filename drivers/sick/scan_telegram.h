// The complete LMDscandata telegram ("sRA LMDscandata" reply to a poll, "sSN LMDscandata"
// event while streaming) as the SICK telegram listing defines it, field by field. Angles are in
// the scanner's own convention (1/10000 degree, 0 degrees to the scanner's right, 90 degrees
// straight ahead); scan_conversion.h turns a telegram into a core::LaserScan.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fleetmap::drivers::sick {

// One output channel: "DIST1".."DIST5" (distances, mm after scaling), "RSSI1".."RSSI5"
// (remission), "ANGL1" (angles). value = raw * scale_factor + scale_offset.
struct ScanChannel {
  std::string content;  // always 5 characters
  float scale_factor = 1.0f;
  float scale_offset = 0.0f;
  int32_t start_angle_1e4deg = 0;    // angle of the first value, 1/10000 degree
  uint16_t angular_step_1e4deg = 0;  // between neighbouring values, 1/10000 degree
  std::vector<uint16_t> values;      // raw; 8-bit channels are widened

  double start_angle_deg() const { return start_angle_1e4deg * 1e-4; }
  double angular_step_deg() const { return angular_step_1e4deg * 1e-4; }
  double Scaled(size_t i) const { return values[i] * double{scale_factor} + scale_offset; }
};

struct ScanEncoder {
  uint32_t position_ticks = 0;
  uint16_t speed_ticks_per_mm = 0;
};

struct ScanPosition {
  float x = 0, y = 0, z = 0;              // mounting position
  float x_rot = 0, y_rot = 0, z_rot = 0;  // mounting rotation
  uint8_t rotation_type = 0;              // 0 none, 1 pitch, 2 roll, 3 free
};

struct ScanClock {
  uint16_t year = 1970;
  uint8_t month = 1, day = 1, hour = 0, minute = 0, second = 0;
  uint32_t microsecond = 0;
};

struct ScanEventInfo {
  std::string type;  // 4 characters: "FDIN" (fixed digital input), "SDIN" (sync input)
  uint32_t encoder_position = 0;
  uint32_t time_us = 0;
  int32_t angular_position_1e4deg = 0;
};

struct ScanTelegram {
  uint16_t version = 1;
  uint16_t device_number = 0;
  uint32_t serial_number = 0;
  uint8_t device_status[2] = {0, 0};  // 0 0: ok
  uint16_t telegram_counter = 0;
  uint16_t scan_counter = 0;
  uint32_t time_since_startup_us = 0;    // device clock at the start of the scan
  uint32_t time_of_transmission_us = 0;  // device clock when the scan was handed to output
  uint8_t input_status[2] = {0, 0};
  uint8_t output_status[2] = {0, 0};
  uint16_t reserved = 0;                     // layer angle on multi-layer devices
  uint32_t scan_frequency_centihz = 0;       // 1/100 Hz: 1500 = 15 Hz
  uint32_t measurement_frequency_100hz = 0;  // shots per second / 100
  std::vector<ScanEncoder> encoders;
  std::vector<ScanChannel> channels16;
  std::vector<ScanChannel> channels8;
  std::optional<ScanPosition> position;
  std::optional<std::string> name;
  std::optional<std::string> comment;
  std::optional<ScanClock> clock;
  std::optional<ScanEventInfo> event;

  double scan_frequency_hz() const { return scan_frequency_centihz / 100.0; }
  // The 16-bit or 8-bit channel with this content, or nullptr.
  const ScanChannel* FindChannel(std::string_view content) const;
};

}  // namespace fleetmap::drivers::sick
