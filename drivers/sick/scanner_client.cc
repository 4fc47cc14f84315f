#include "drivers/sick/scanner_client.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <thread>

#include "drivers/sick/commands.h"
#include "drivers/sick/scan_telegram_codec.h"

namespace fleetmap::drivers::sick {
namespace {

double SteadyNowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

TelegramSplitterOptions SplitterOptions(const ScannerClientOptions& o) {
  TelegramSplitterOptions s;
  s.protocol = o.protocol;
  s.max_payload_bytes = o.max_payload_bytes;
  return s;
}

}  // namespace

double RealtimeNowS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

core::Status ScannerClientOptions::Validate() const {
  if (host.empty()) return core::InvalidArgument("scanner_client.host is empty");
  if (port <= 0 || port > 65535) return core::InvalidArgument("scanner_client.port out of range");
  if (!(connect_timeout_s > 0.0)) {
    return core::InvalidArgument("scanner_client.connect_timeout_s must be positive");
  }
  if (!(silence_timeout_s > 0.0)) {
    return core::InvalidArgument("scanner_client.silence_timeout_s must be positive");
  }
  if (!(reconnect_backoff_initial_s > 0.0)) {
    return core::InvalidArgument("scanner_client.reconnect_backoff_initial_s must be positive");
  }
  if (!(reconnect_backoff_max_s >= reconnect_backoff_initial_s)) {
    return core::InvalidArgument("scanner_client.reconnect_backoff_max_s < initial");
  }
  if (max_payload_bytes < 16) {
    return core::InvalidArgument("scanner_client.max_payload_bytes must be >= 16");
  }
  return clock.Validate();
}

ScannerClient::ScannerClient(ScannerClientOptions options, Clock host_clock)
    : options_(std::move(options)),
      host_clock_(std::move(host_clock)),
      splitter_(SplitterOptions(options_)),
      device_clock_(options_.clock),
      backoff_s_(options_.reconnect_backoff_initial_s) {
  assert(options_.Validate().ok());
}

ScannerClientStats ScannerClient::stats() const {
  ScannerClientStats s = stats_;
  s.framing = splitter_.stats();
  return s;
}

core::Status ScannerClient::ConnectAndStart() {
  core::Result<TcpConnection> c =
      TcpConnection::Connect(options_.host, options_.port, options_.connect_timeout_s);
  if (!c.ok()) return c.status();
  std::string request;
  if (options_.login)
    request += FrameTelegram(options_.protocol, SetAccessModeRequest(options_.protocol));
  if (options_.streaming) {
    request += FrameTelegram(options_.protocol, ScanStreamRequest(options_.protocol, true));
  }
  if (!request.empty()) {
    FLEETMAP_RETURN_IF_ERROR(c->WriteAll(request, options_.connect_timeout_s));
  }
  connection_.emplace(std::move(c).value());
  splitter_.Reset();
  poll_outstanding_ = false;
  last_bytes_s_ = SteadyNowS();
  ++stats_.connects;
  return core::OkStatus();
}

void ScannerClient::Disconnect(const core::Status& why) {
  if (connection_) ++stats_.disconnects;
  connection_.reset();
  last_error_ = why;
  next_connect_s_ = SteadyNowS() + backoff_s_;
  backoff_s_ = std::min(2.0 * backoff_s_, options_.reconnect_backoff_max_s);
}

void ScannerClient::Close() {
  if (connection_ && options_.streaming) {
    const std::string stop =
        FrameTelegram(options_.protocol, ScanStreamRequest(options_.protocol, false));
    (void)connection_->WriteAll(stop, 0.2);
  }
  connection_.reset();
}

std::optional<ReceivedScan> ScannerClient::Handle(const std::string& payload) {
  if (IsScanTelegram(payload)) {
    ReceivedScan scan;
    const core::Status s = ParseScanTelegramInto(payload, options_.protocol, scan.telegram);
    if (!s.ok()) {
      ++stats_.bad_scans;
      last_error_ = s;
      return std::nullopt;
    }
    scan.host_receive_s = last_bytes_host_s_;
    device_clock_.Map(scan.telegram.time_of_transmission_us, scan.host_receive_s);
    scan.stamp_s = device_clock_.ToHost(scan.telegram.time_since_startup_us);
    poll_outstanding_ = false;
    ++stats_.scans;
    backoff_s_ = options_.reconnect_backoff_initial_s;
    return scan;
  }
  const core::Result<ParsedCommand> c = ParseCommand(payload, options_.protocol);
  if (c.ok() && c->type == "sFA") {
    ++stats_.error_replies;
    last_error_ = core::FailedPrecondition("scanner refused a request (sFA " +
                                           std::to_string(c->value) + ")");
  } else if (c.ok() && c->type == "sAN" && c->name == "SetAccessMode" && c->value == 0) {
    ++stats_.login_refused;
    last_error_ = core::FailedPrecondition("scanner refused the login (SetAccessMode)");
  } else {
    ++stats_.other_telegrams;
  }
  return std::nullopt;
}

std::optional<ReceivedScan> ScannerClient::TakeBufferedScan() {
  while (std::optional<std::string> payload = splitter_.Next()) {
    if (std::optional<ReceivedScan> scan = Handle(*payload)) return scan;
  }
  return std::nullopt;
}

core::Status ScannerClient::ReadOnce(double wait_s) {
  if (!options_.streaming && !poll_outstanding_) {
    FLEETMAP_RETURN_IF_ERROR(connection_->WriteAll(
        FrameTelegram(options_.protocol, ScanPollRequest()), options_.connect_timeout_s));
    poll_outstanding_ = true;
  }
  uint8_t buffer[16384];
  core::Result<size_t> n = connection_->Read(buffer, sizeof(buffer), wait_s);
  if (!n.ok()) return n.status();
  if (*n > 0) {
    last_bytes_s_ = SteadyNowS();
    last_bytes_host_s_ = host_clock_();
    splitter_.Feed(buffer, *n);
  }
  return core::OkStatus();
}

core::Result<ReceivedScan> ScannerClient::NextScan(double timeout_s) {
  const double deadline = SteadyNowS() + timeout_s;
  while (true) {
    if (std::optional<ReceivedScan> scan = TakeBufferedScan()) return std::move(*scan);
    const double now = SteadyNowS();
    if (now >= deadline) {
      return core::IoError(
          "no scan within " + std::to_string(timeout_s) + " s" +
          (last_error_.ok() ? "" : " (last error: " + last_error_.ToString() + ")"));
    }
    if (!connection_) {
      if (now < next_connect_s_) {
        std::this_thread::sleep_for(
            std::chrono::duration<double>(std::min(next_connect_s_, deadline) - now));
        continue;
      }
      const core::Status s = ConnectAndStart();
      if (!s.ok()) {
        ++stats_.connect_failures;
        Disconnect(s);
      }
      continue;
    }
    const double silence_end = last_bytes_s_ + options_.silence_timeout_s;
    if (now >= silence_end) {
      ++stats_.silences;
      Disconnect(
          core::IoError("scanner silent for " + std::to_string(options_.silence_timeout_s) + " s"));
      continue;
    }
    const core::Status s = ReadOnce(std::min(deadline, silence_end) - now);
    if (!s.ok()) Disconnect(s);
  }
}

}  // namespace fleetmap::drivers::sick
