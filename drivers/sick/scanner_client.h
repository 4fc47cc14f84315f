// The SICK scanner client: connects over TCP, drives the device's start sequence (login,
// LMCstartmeas, Run, subscribe; start_sequence.h), waits for the device to spin up, and hands
// out parsed scans stamped in host time (or polls for them). It survives everything a network
// and a scanner do: telegrams split across segments, garbage, bad checksums, a scanner that
// disappears, stops sending or sends bytes that form no scan (reconnect with exponential
// backoff, and the whole start sequence again). One thread calls NextScan in a loop.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "core/result.h"
#include "drivers/sick/commands.h"
#include "drivers/sick/device_clock.h"
#include "drivers/sick/scan_telegram.h"
#include "drivers/sick/tcp_connection.h"
#include "drivers/sick/telegram_splitter.h"

namespace fleetmap::drivers::sick {

struct ScannerClientOptions {
  std::string host = "192.168.0.1";  // the SICK factory default address
  int port = 2112;                   // 2111 and 2112 both speak CoLa-A or CoLa-B as configured
  ColaProtocol protocol = ColaProtocol::kColaB;
  double connect_timeout_s = 2.0;  // per connection attempt, and per start-up request; > 0
  // After the start sequence, a device spins up for seconds before its first scan; > 0.
  double first_scan_timeout_s = 10.0;
  double silence_timeout_s = 1.0;            // then no valid scan for this long: reconnect; > 0
  double reconnect_backoff_initial_s = 0.1;  // first wait before reconnecting; > 0
  double reconnect_backoff_max_s = 5.0;      // the wait doubles up to this; >= initial
  bool login = true;                         // send SetAccessMode (level 3) before starting
  bool start_measurement = true;  // send LMCstartmeas and Run (the device measures only then)
  bool streaming = true;          // sEN LMDscandata 1; false: one sRN LMDscandata poll per scan
  size_t max_payload_bytes = 1 << 20;  // longer telegrams are garbage (telegram_splitter.h)
  DeviceClockOptions clock;
  core::Status Validate() const;
};

struct ScannerClientStats {
  uint64_t connects = 0;          // successful connections (the first one included)
  uint64_t connect_failures = 0;  // attempts that failed (refused, timed out)
  uint64_t disconnects = 0;       // connections dropped: peer closed, error or silence
  uint64_t silences = 0;          // of which: no valid scan in time (first or next)
  uint64_t start_refusals = 0;    // LMCstartmeas or Run refused (the start went on)
  uint64_t scans = 0;             // scans handed out
  uint64_t bad_scans = 0;         // scan telegrams that did not parse
  uint64_t error_replies = 0;     // sFA: the scanner refused a request
  uint64_t login_refused = 0;     // sAN SetAccessMode 0
  uint64_t other_telegrams = 0;   // acknowledgements and events we do not use
  TelegramSplitterStats framing;  // over all connections: garbage, bad checksums, oversized
  DeviceState device_state = DeviceState::kUnknown;  // last SCdevicestate reply
};

struct ReceivedScan {
  ScanTelegram telegram;
  double host_receive_s = 0.0;  // host clock when the telegram's last byte arrived
  double stamp_s = 0.0;         // scan start (device time) mapped to the host clock
};

// Seconds of CLOCK_REALTIME, the clock SocketCAN stamps frames with.
double RealtimeNowS();

class ScannerClient {
 public:
  using Clock = std::function<double()>;
  // `host_clock` stamps received telegrams; timeouts always use the monotonic clock.
  explicit ScannerClient(ScannerClientOptions options, Clock host_clock = RealtimeNowS);
  ~ScannerClient() { Close(); }

  // The next scan, waiting up to `timeout_s` and (re)connecting as needed. IoError when none
  // arrived in time; its message says why (the last connection error, for instance).
  core::Result<ReceivedScan> NextScan(double timeout_s);
  // Stops streaming (best effort) and disconnects. NextScan reconnects.
  void Close();

  bool connected() const { return connection_.has_value(); }
  // Why the last connection ended or failed, or a refusal during its start; ok if none yet.
  const core::Status& last_error() const { return last_error_; }
  ScannerClientStats stats() const;
  const ScannerClientOptions& options() const { return options_; }

 private:
  core::Status ConnectAndStart();
  void Disconnect(const core::Status& why);
  // When the connection has gone without a valid scan for too long: the reason, else ok.
  core::Status CheckSilence(double now) const;
  double SilenceEnd() const;
  core::Status ReadOnce(double wait_s);
  core::Status SendPendingRequests(double now);
  std::optional<ReceivedScan> TakeBufferedScan();
  std::optional<ReceivedScan> Handle(const std::string& payload);

  const ScannerClientOptions options_;
  const Clock host_clock_;
  std::optional<TcpConnection> connection_;
  TelegramSplitter splitter_;
  DeviceClock device_clock_;
  ScannerClientStats stats_;
  core::Status last_error_;
  double next_connect_s_ = 0.0;  // monotonic
  double backoff_s_;
  double connected_s_ = 0.0;       // monotonic
  double last_scan_s_ = -1.0;      // monotonic; < 0: none yet on this connection
  double next_state_query_s_ = 0;  // monotonic; SCdevicestate while waiting for the first scan
  uint64_t garbage_at_last_scan_ = 0;
  double last_bytes_host_s_ = 0.0;
  bool poll_outstanding_ = false;
};

}  // namespace fleetmap::drivers::sick
