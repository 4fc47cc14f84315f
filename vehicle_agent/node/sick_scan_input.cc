#include "vehicle_agent/node/sick_scan_input.h"

namespace fleetmap::vehicle_agent::node {

core::Status SickInputOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(client.Validate().WithContext("inputs.sick"));
  return conversion.Validate().WithContext("inputs.sick");
}

SickScanInput::SickScanInput(const SickInputOptions& options, LogSink log)
    : options_(options), log_(std::move(log)), client_(options.client) {}

std::string SickScanInput::endpoint() const {
  return options_.client.host + ":" + std::to_string(options_.client.port) + " (" +
         drivers::sick::ColaProtocolName(options_.client.protocol) + ")";
}

void SickScanInput::LogConnection(const core::Status& last_error) {
  const bool now = client_.connected();
  if (now == was_connected_) return;
  was_connected_ = now;
  if (!log_) return;
  if (now) {
    log_(LogLevel::kInfo, "scanner connected: " + endpoint());
  } else {
    log_(LogLevel::kWarning, "scanner " + endpoint() + " lost (" + last_error.ToString() +
                                 "): reconnecting with backoff");
  }
}

std::optional<DriverScan> SickScanInput::Next(double timeout_s) {
  core::Result<drivers::sick::ReceivedScan> received = client_.NextScan(timeout_s);
  LogConnection(received.ok() ? core::OkStatus() : received.status());
  if (!received.ok()) return std::nullopt;
  core::Result<core::LaserScan> scan =
      drivers::sick::ToLaserScan(received->telegram, options_.conversion, received->stamp_s);
  if (!scan.ok()) {
    if (conversion_errors_++ == 0 && log_)
      log_(LogLevel::kWarning, "scanner telegram not usable (logged once; counted in STATUS): " +
                                   scan.status().ToString());
    return std::nullopt;
  }
  DriverScan out;
  out.scan = std::move(scan).value();
  out.device_stamp_s = received->telegram.time_since_startup_us * 1e-6;
  return out;
}

NamedCounters SickScanInput::Counters() const {
  const drivers::sick::ScannerClientStats s = client_.stats();
  const auto n = [](uint64_t v) { return static_cast<int64_t>(v); };
  return {
      {"scanner_connects", n(s.connects)},
      {"scanner_reconnects", s.connects > 0 ? n(s.connects - 1) : 0},
      {"scanner_connect_failures", n(s.connect_failures)},
      {"scanner_disconnects", n(s.disconnects)},
      {"scanner_silences", n(s.silences)},
      {"scanner_scans", n(s.scans)},
      {"scanner_bad_scans", n(s.bad_scans)},
      {"scanner_conversion_errors", conversion_errors_},
      {"scanner_garbage_bytes", n(s.framing.garbage_bytes)},
      {"scanner_bad_checksums", n(s.framing.bad_checksums)},
  };
}

}  // namespace fleetmap::vehicle_agent::node
