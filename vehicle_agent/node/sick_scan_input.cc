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

void SickScanInput::LogConnection() {
  const drivers::sick::ScannerClientStats s = client_.stats();
  const uint64_t losses = s.disconnects + s.connect_failures;
  const bool lost = losses > seen_losses_;
  const bool connected = s.connects > seen_connects_;
  losses_since_scan_ += losses - seen_losses_;
  seen_losses_ = losses;
  seen_connects_ = s.connects;
  if (!log_ || loss_logged_) return;
  if (connected && !lost) log_(LogLevel::kInfo, "scanner connected: " + endpoint());
  if (!lost) return;
  loss_logged_ = true;
  log_(LogLevel::kWarning, "scanner " + endpoint() + " lost (" + client_.last_error().ToString() +
                               "): reconnecting with backoff, again until a scan comes " +
                               "(counted in STATUS, not logged)");
}

std::optional<DriverScan> SickScanInput::Next(double timeout_s) {
  core::Result<drivers::sick::ReceivedScan> received = client_.NextScan(timeout_s);
  LogConnection();
  if (!received.ok()) return std::nullopt;
  if (loss_logged_ && log_) {
    log_(LogLevel::kInfo, "scanner " + endpoint() + " sends scans again, after " +
                              std::to_string(losses_since_scan_) + " lost connection(s)");
  }
  loss_logged_ = false;
  losses_since_scan_ = 0;
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
