#include "drivers/sick/scanner_client.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <thread>
#include <vector>

#include "drivers/sick/commands.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "drivers/sick/start_sequence.h"

namespace fleetmap::drivers::sick {
namespace {

// While a device spins up, its state is asked this often (the answer goes into the stats and
// into the reason given when no scan came).
constexpr double kDeviceStateQueryPeriodS = 1.0;

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
  if (!(first_scan_timeout_s > 0.0)) {
    return core::InvalidArgument("scanner_client.first_scan_timeout_s must be positive");
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
  splitter_.Reset();
  StartSequenceOptions start;
  start.protocol = options_.protocol;
  start.login = options_.login;
  start.start_measurement = options_.start_measurement;
  start.streaming = options_.streaming;
  start.reply_timeout_s = options_.connect_timeout_s;
  const StartSequenceResult started = RunStartSequence(*c, splitter_, start);
  stats_.error_replies += started.error_replies;
  stats_.login_refused += started.login_refused ? 1 : 0;
  stats_.other_telegrams += started.other_telegrams;
  stats_.start_refusals += started.refused.size();
  if (!started.status.ok()) return started.status;
  if (!started.refused.empty()) {
    last_error_ = core::FailedPrecondition("scanner " + started.refused.front());
  }
  connection_.emplace(std::move(c).value());
  poll_outstanding_ = false;
  connected_s_ = MonotonicNowS();
  last_scan_s_ = -1.0;
  next_state_query_s_ = connected_s_;
  garbage_at_last_scan_ = splitter_.stats().garbage_bytes;
  stats_.device_state = DeviceState::kUnknown;
  ++stats_.connects;
  return core::OkStatus();
}

void ScannerClient::Disconnect(const core::Status& why) {
  if (connection_) ++stats_.disconnects;
  connection_.reset();
  last_error_ = why;
  next_connect_s_ = MonotonicNowS() + backoff_s_;
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
    last_scan_s_ = MonotonicNowS();
    garbage_at_last_scan_ = splitter_.stats().garbage_bytes;
    ++stats_.scans;
    backoff_s_ = options_.reconnect_backoff_initial_s;
    return scan;
  }
  const core::Result<ParsedCommand> c = ParseCommand(payload, options_.protocol);
  if (c.ok() && c->type == "sFA") {
    ++stats_.error_replies;
    last_error_ = core::FailedPrecondition("scanner refused a request (sFA " +
                                           std::to_string(c->value) + ")");
  } else if (c.ok() && c->type == "sRA" && c->name == "SCdevicestate" && c->has_value) {
    stats_.device_state = c->value <= 2 ? static_cast<DeviceState>(c->value) : DeviceState::kError;
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

core::Status ScannerClient::SendPendingRequests(double now) {
  std::string requests;
  if (!options_.streaming && !poll_outstanding_) {
    requests += FrameTelegram(options_.protocol, ScanPollRequest());
    poll_outstanding_ = true;
  }
  if (last_scan_s_ < 0.0 && now >= next_state_query_s_) {
    requests += FrameTelegram(options_.protocol, DeviceStateRequest());
    next_state_query_s_ = now + kDeviceStateQueryPeriodS;
  }
  if (requests.empty()) return core::OkStatus();
  return connection_->WriteAll(requests, options_.connect_timeout_s);
}

core::Status ScannerClient::ReadOnce(double wait_s) {
  FLEETMAP_RETURN_IF_ERROR(SendPendingRequests(MonotonicNowS()));
  if (last_scan_s_ < 0.0)
    wait_s = std::min(wait_s, std::max(0.0, next_state_query_s_ - MonotonicNowS()));
  uint8_t buffer[16384];
  core::Result<size_t> n = connection_->Read(buffer, sizeof(buffer), wait_s);
  if (!n.ok()) return n.status();
  if (*n > 0) {
    last_bytes_host_s_ = host_clock_();
    splitter_.Feed(buffer, *n);
  }
  return core::OkStatus();
}

double ScannerClient::SilenceEnd() const {
  return last_scan_s_ < 0.0 ? connected_s_ + options_.first_scan_timeout_s
                            : last_scan_s_ + options_.silence_timeout_s;
}

core::Status ScannerClient::CheckSilence(double now) const {
  if (now < SilenceEnd()) return core::OkStatus();
  const uint64_t garbage = splitter_.stats().garbage_bytes - garbage_at_last_scan_;
  std::vector<std::string> why;
  if (last_scan_s_ < 0.0)
    why.push_back("device state " + std::string(DeviceStateName(stats_.device_state)));
  if (garbage > 0) why.push_back(std::to_string(garbage) + " bytes meanwhile formed no telegram");
  std::string text =
      last_scan_s_ < 0.0
          ? "no scan within " + std::to_string(options_.first_scan_timeout_s) + " s of connecting"
          : "no valid scan for " + std::to_string(options_.silence_timeout_s) + " s";
  for (size_t i = 0; i < why.size(); ++i) text += (i == 0 ? " (" : "; ") + why[i];
  return core::IoError(why.empty() ? text : text + ")");
}

core::Result<ReceivedScan> ScannerClient::NextScan(double timeout_s) {
  const double deadline = MonotonicNowS() + timeout_s;
  while (true) {
    if (std::optional<ReceivedScan> scan = TakeBufferedScan()) return std::move(*scan);
    const double now = MonotonicNowS();
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
    if (core::Status silent = CheckSilence(now); !silent.ok()) {
      ++stats_.silences;
      Disconnect(silent);
      continue;
    }
    const core::Status s = ReadOnce(std::min(deadline, SilenceEnd()) - now);
    if (!s.ok()) Disconnect(s);
  }
}

}  // namespace fleetmap::drivers::sick
