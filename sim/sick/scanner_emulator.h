// A SICK scanner on a TCP port, for running the real driver end to end without hardware. It
// behaves as the devices do (docs/drivers.md): it measures only after sMN LMCstartmeas, then
// spins up for `spin_up_s` (SCdevicestate busy) before its first scan; a login puts it into
// the configuration level, where it sends no scans until sMN Run; sEN LMDscandata 1/0
// subscribes (sSN scans at the source's rate) and sRN LMDscandata polls (one sRA scan, sent
// once the device measures). CoLa-A or CoLa-B; one client at a time: a second connection is
// accepted and closed at once. Faults real networks and scanners produce can be switched on
// for tests: telegrams split into small writes, garbage between telegrams, corrupted
// checksums, a scanner that falls silent, scans framed in CoLa-B on a CoLa-A port.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "core/result.h"
#include "drivers/sick/cola_frame.h"
#include "drivers/sick/tcp_connection.h"
#include "sim/sick/scan_source.h"

namespace fleetmap::sim::sick {

struct EmulatorOptions {
  std::string bind_address = "127.0.0.1";
  int port = 2112;  // 0: any free port (port() tells which)
  drivers::sick::ColaProtocol protocol = drivers::sick::ColaProtocol::kColaB;
  bool require_login = false;  // refuse LMCstartmeas, sEN and sRN with sFA before a login
  double speed_factor = 1.0;   // scans come speed_factor times faster than real; > 0
  double spin_up_s = 1.0;      // from LMCstartmeas to the first scan (real time); >= 0
  // Measuring from power-up, as if LMCstartmeas had come before (the device still needs Run
  // after a login).
  bool measuring_at_power_up = false;
  // Fault injection (0: off).
  size_t max_write_bytes = 0;     // write every telegram in pieces of at most this size
  size_t garbage_every = 0;       // garbage bytes before every n-th scan
  size_t corrupt_every = 0;       // every n-th scan with a wrong CoLa-B checksum / cut CoLa-A
  size_t silent_after_scans = 0;  // on the first connection, stop sending after n scans
  bool cola_b_scans = false;      // scans framed in CoLa-B whatever the protocol (as on port 2111
                                  // of SICK's emulator: replies in ASCII, scans binary)
  core::Status Validate() const;
};

struct EmulatorStats {
  std::atomic<uint64_t> connections{0};
  std::atomic<uint64_t> scans_sent{0};
  std::atomic<uint64_t> requests{0};
  std::atomic<uint64_t> logins{0};
  std::atomic<uint64_t> start_requests{0};       // LMCstartmeas
  std::atomic<uint64_t> run_requests{0};         // Run
  std::atomic<uint64_t> refused_connections{0};  // a second client while one was served
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
  struct Session {  // one client's connection
    bool logged_in = false;
    bool streaming = false;
    bool poll_pending = false;
  };

  void AcceptLoop();
  void Serve(drivers::sick::TcpConnection& client, bool first);
  void RefuseWaitingClients();
  // Handles one request; returns false if the connection should close.
  bool HandleRequest(drivers::sick::TcpConnection& client, const std::string& payload,
                     Session& session);
  bool Reply(drivers::sick::TcpConnection& client, const char* type, const char* name,
             uint8_t value);
  // Measuring, spun up and in run mode: scans go out.
  bool Producing(double now) const;
  bool SendScan(drivers::sick::TcpConnection& client, const char* type);
  bool Send(drivers::sick::TcpConnection& client, const std::string& bytes);

  const EmulatorOptions options_;
  std::unique_ptr<ScanSource> source_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  // The device, over connections (only the serving thread touches it).
  bool measuring_ = false;
  double ready_s_ = 0.0;  // monotonic: the first scan once measuring
  bool run_mode_ = true;  // false from a login until Run
  EmulatorStats stats_;
};

}  // namespace fleetmap::sim::sick
