// Telegrams built in code for the SICK tests.
#pragma once

#include <string>

#include "drivers/sick/scan_telegram.h"

namespace fleetmap::drivers::sick::testing {

// A TiM781S-like scan: 811 points from -45 degrees at 1/3 degree, DIST1 and RSSI1, 15 Hz,
// with every optional block filled so that round trips cover them all.
inline ScanTelegram Tim781Like(bool all_blocks = true) {
  ScanTelegram t;
  t.serial_number = 18480390;
  t.telegram_counter = 7;
  t.scan_counter = 8;
  t.time_since_startup_us = 123456789;
  t.time_of_transmission_us = 123460000;
  t.scan_frequency_centihz = 1500;
  t.measurement_frequency_100hz = 162;
  for (const char* name : {"DIST1", "RSSI1"}) {
    ScanChannel c;
    c.content = name;
    c.start_angle_1e4deg = -450000;
    c.angular_step_1e4deg = 3333;
    for (int i = 0; i < 811; ++i) c.values.push_back(static_cast<uint16_t>(1000 + 37 * i % 20000));
    t.channels16.push_back(c);
  }
  if (all_blocks) {
    t.encoders.push_back({0xDEADBEEF, 12});
    ScanChannel rssi8 = t.channels16[1];
    rssi8.content = "RSSI2";
    for (auto& v : rssi8.values) v &= 0xFF;
    t.channels8.push_back(rssi8);
    t.position = ScanPosition{1.5f, -2.0f, 0.25f, 0.0f, 0.0f, 3.14f, 3};
    t.name = "Daniyal";
    t.comment = "a comment with spaces";
    t.clock = ScanClock{2024, 5, 17, 13, 45, 59, 123456};
    t.event = ScanEventInfo{"FDIN", 42, 99999, -12345};
  }
  return t;
}

}  // namespace fleetmap::drivers::sick::testing
