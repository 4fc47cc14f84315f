// The SICK scanner client's receive path without the socket (drivers/sick/scanner_client.cc):
// a TCP byte stream cut into telegrams by the TelegramSplitter, each telegram parsed as the
// client does (LMDscandata into one reused ScanTelegram, else a command reply), scans mapped
// through the device clock and converted to LaserScans. Shared by cola_a_fuzz and cola_b_fuzz.
//
// Input: byte 0 picks the size of the pieces the stream arrives in (1 + b * b bytes, so both
// byte-by-byte arrival and whole telegrams occur); the rest is the stream. At most 256 pieces:
// the CoLa-A splitter rescans an unfinished telegram on every piece, so a 12 KB telegram fed
// byte by byte costs seconds under the sanitizers and would starve the fuzzer.
#pragma once

#include <algorithm>
#include <string>

#include "drivers/sick/commands.h"
#include "drivers/sick/device_clock.h"
#include "drivers/sick/scan_conversion.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "drivers/sick/telegram_splitter.h"
#include "fuzz/fuzz_check.h"

namespace fleetmap::fuzz {

class ColaStreamTarget {
 public:
  explicit ColaStreamTarget(drivers::sick::ColaProtocol protocol) : protocol_(protocol) {}

  void Run(const std::string& stream, size_t piece_bytes) {
    piece_bytes = std::max(piece_bytes, stream.size() / 256);
    drivers::sick::TelegramSplitterOptions options;
    options.protocol = protocol_;
    options.max_payload_bytes = 1 << 16;  // small enough that inputs reach the limit
    drivers::sick::TelegramSplitter splitter(options);
    drivers::sick::DeviceClock clock;
    drivers::sick::ScanTelegram telegram;  // reused, as the client reuses its vectors
    double host_s = 1e9;
    for (size_t at = 0; at < stream.size(); at += piece_bytes) {
      const std::string piece = stream.substr(at, piece_bytes);
      splitter.Feed(piece);
      while (std::optional<std::string> payload = splitter.Next()) {
        Handle(*payload, clock, telegram, host_s += 0.05);
      }
      // The buffer holds at most one maximal telegram and its framing plus one piece.
      FUZZ_REQUIRE(splitter.buffered_bytes() <= options.max_payload_bytes + 10 + piece.size());
    }
  }

 private:
  void Handle(const std::string& payload, drivers::sick::DeviceClock& clock,
              drivers::sick::ScanTelegram& telegram, double host_s) {
    namespace sick = drivers::sick;
    (void)sick::SplitCommand(payload);
    if (!sick::IsScanTelegram(payload)) {
      (void)sick::ParseCommand(payload, protocol_);
      return;
    }
    if (!sick::ParseScanTelegramInto(payload, protocol_, telegram).ok()) return;
    clock.Map(telegram.time_of_transmission_us, host_s);
    const double stamp_s = clock.ToHost(telegram.time_since_startup_us);
    core::Result<core::LaserScan> scan = sick::ToLaserScan(telegram, {}, stamp_s);
    if (scan.ok()) (void)scan->Validate();
  }

  const drivers::sick::ColaProtocol protocol_;
};

}  // namespace fleetmap::fuzz
