// Scans from a SICK scanner over TCP (drivers/sick's ScannerClient, with its reconnect and
// backoff), converted to core::LaserScan in host time. The agent's loop calls Next with a
// short wait, so the LCM links are served between scans. A lost connection is logged once
// with its reason; the reconnects that follow without a scan (a scanner that stays away or
// sends nothing usable) are counted for STATUS, and the first scan after them is logged.
#pragma once

#include <optional>
#include <string>

#include "drivers/sick/scan_conversion.h"
#include "drivers/sick/scanner_client.h"
#include "vehicle_agent/node/agent_counters.h"
#include "vehicle_agent/node/node_io.h"

namespace fleetmap::vehicle_agent::node {

struct SickInputOptions {
  drivers::sick::ScannerClientOptions client;       // host, port, protocol, timeouts
  drivers::sick::ScanConversionOptions conversion;  // channels, range limits
  core::Status Validate() const;
};

struct DriverScan {
  core::LaserScan scan;         // stamped in host time (CLOCK_REALTIME)
  double device_stamp_s = 0.0;  // the scanner's own clock: seconds since its power-up
};

class SickScanInput {
 public:
  // `options` must pass Validate(); `log` may be empty.
  SickScanInput(const SickInputOptions& options, LogSink log);

  // The next scan, waiting up to `timeout_s` (and (re)connecting as the client's backoff
  // allows); nothing when none arrived in time or the telegram did not convert (counted).
  std::optional<DriverScan> Next(double timeout_s);

  // scanner_connects, scanner_reconnects, scanner_disconnects, scanner_silences,
  // scanner_scans, scanner_bad_scans, scanner_conversion_errors, scanner_garbage_bytes,
  // scanner_bad_checksums.
  NamedCounters Counters() const;
  bool connected() const { return client_.connected(); }
  std::string endpoint() const;

 private:
  void LogConnection();

  const SickInputOptions options_;
  LogSink log_;
  drivers::sick::ScannerClient client_;
  uint64_t seen_connects_ = 0;  // the client's counters when last looked at
  uint64_t seen_losses_ = 0;    // disconnects and failed attempts
  bool loss_logged_ = false;    // a loss was logged and no scan has come since
  uint64_t losses_since_scan_ = 0;
  int64_t conversion_errors_ = 0;
};

}  // namespace fleetmap::vehicle_agent::node
