// The requests that bring a SICK scanner from power-up, or from a login, to a stream of scans.
// They go one at a time, each waiting for its reply, in the order SICK's own driver uses
// (sick_scan_xd, sick_scan_common.cpp: LMCstartmeas, Run, then LMDscandata; docs/drivers.md):
//   sMN SetAccessMode 3 F4724744  ->  sAN SetAccessMode 1   (0: refused; the start stops here)
//   sMN LMCstartmeas              ->  sAN LMCstartmeas 0    (laser and motor on)
//   sMN Run                       ->  sAN Run 1             (leave the configuration level)
//   sEN LMDscandata 1             ->  sEA LMDscandata 1     (streaming only; refused: stops)
// A refused LMCstartmeas or Run is only noted: some devices (a TiM240) do not know the
// command and measure anyway; the wait for the first scan then decides. After the sequence a
// device still spins up for seconds before its first scan.
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "drivers/sick/cola_frame.h"
#include "drivers/sick/tcp_connection.h"
#include "drivers/sick/telegram_splitter.h"

namespace fleetmap::drivers::sick {

struct StartSequenceOptions {
  ColaProtocol protocol = ColaProtocol::kColaB;
  bool login = true;              // SetAccessMode first
  bool start_measurement = true;  // LMCstartmeas and Run
  bool streaming = true;          // sEN LMDscandata 1 last
  double reply_timeout_s = 2.0;   // per request; > 0
};

// The request payloads (unframed), in the order they are sent.
std::vector<std::string> StartRequests(const StartSequenceOptions& options);

struct StartSequenceResult {
  // Not ok when the start failed: no reply within the timeout, the connection failed, the
  // login or the scan subscription refused.
  core::Status status;
  std::vector<std::string> refused;  // requests refused without stopping the start
  size_t error_replies = 0;          // sFA replies
  bool login_refused = false;        // sAN SetAccessMode 0
  size_t other_telegrams = 0;        // scans and events that came in between, dropped
};

// Sends the requests over `connection` and reads the replies through `splitter`, whose
// remaining bytes (the first scans, perhaps) stay buffered for the caller.
StartSequenceResult RunStartSequence(TcpConnection& connection, TelegramSplitter& splitter,
                                     const StartSequenceOptions& options);

}  // namespace fleetmap::drivers::sick
