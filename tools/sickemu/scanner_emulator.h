// A SICK scanner on a TCP port, for running the real driver end to end without hardware:
// answers SetAccessMode, sEN LMDscandata 1/0 (then streams sSN scans at the source's rate) and
// sRN LMDscandata (one sRA scan), in CoLa-A or CoLa-B, one client at a time. Faults real
// networks and scanners produce can be switched on for tests: telegrams split into small
// writes, garbage between telegrams, corrupted checksums, a scanner that falls silent.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "core/result.h"
#include "drivers/sick/cola_frame.h"
#include "drivers/sick/tcp_connection.h"
#include "tools/sickemu/scan_source.h"

namespace fleetmap::sickemu {

struct EmulatorOptions {
  std::string bind_address = "127.0.0.1";
  int port = 2112;  // 0: any free port (port() tells which)
  drivers::sick::ColaProtocol protocol = drivers::sick::ColaProtocol::kColaB;
  bool require_login = false;  // refuse sEN/sRN with sFA before SetAccessMode
  double speed_factor = 1.0;   // scans come speed_factor times faster than real; > 0
  // Fault injection (0: off).
  size_t max_write_bytes = 0;     // write every telegram in pieces of at most this size
  size_t garbage_every = 0;       // garbage bytes before every n-th scan
  size_t corrupt_every = 0;       // every n-th scan with a wrong CoLa-B checksum / cut CoLa-A
  size_t silent_after_scans = 0;  // on the first connection, stop sending after n scans
  core::Status Validate() const;
};

struct EmulatorStats {
  std::atomic<uint64_t> connections{0};
  std::atomic<uint64_t> scans_sent{0};
  std::atomic<uint64_t> requests{0};
  std::atomic<uint64_t> logins{0};
};

class ScannerEmulator {
 public:
  ScannerEmulator(EmulatorOptions options, std::unique_ptr<ScanSource> source);
  ~ScannerEmulator() { Stop(); }

  // Binds and listens, then serves on a thread of its own.
  core::Status Start();
  void Stop();
  int port() const { return port_; }
  const EmulatorStats& stats() const { return stats_; }

 private:
  void AcceptLoop();
  void Serve(drivers::sick::TcpConnection& client, bool first);
  // Handles one request; returns false if the connection should close.
  bool HandleRequest(drivers::sick::TcpConnection& client, const std::string& payload,
                     bool& logged_in, bool& streaming);
  bool SendScan(drivers::sick::TcpConnection& client, const char* type);
  bool Send(drivers::sick::TcpConnection& client, const std::string& bytes);

  const EmulatorOptions options_;
  std::unique_ptr<ScanSource> source_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  EmulatorStats stats_;
};

}  // namespace fleetmap::sickemu
