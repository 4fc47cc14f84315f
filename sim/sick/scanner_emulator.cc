#include "sim/sick/scanner_emulator.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "drivers/sick/commands.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "drivers/sick/telegram_splitter.h"

namespace fleetmap::sim::sick {
namespace {

using drivers::sick::ColaProtocol;
using drivers::sick::MonotonicNowS;
using drivers::sick::TcpConnection;

constexpr double kWriteTimeoutS = 2.0;

}  // namespace

core::Status EmulatorOptions::Validate() const {
  if (port < 0 || port > 65535) return core::InvalidArgument("emulator.port out of range");
  if (!(speed_factor > 0.0)) return core::InvalidArgument("emulator.speed_factor must be positive");
  if (!(spin_up_s >= 0.0)) return core::InvalidArgument("emulator.spin_up_s must be >= 0");
  return core::OkStatus();
}

ScannerEmulator::ScannerEmulator(EmulatorOptions options, std::unique_ptr<ScanSource> source)
    : options_(std::move(options)), source_(std::move(source)) {}

core::Status ScannerEmulator::Start() {
  FLEETMAP_RETURN_IF_ERROR(options_.Validate());
  measuring_ = options_.measuring_at_power_up;
  listen_fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (listen_fd_ < 0) return core::IoError(std::string("socket: ") + std::strerror(errno));
  const int one = 1;
  setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(options_.port));
  if (inet_pton(AF_INET, options_.bind_address.c_str(), &addr.sin_addr) != 1) {
    return core::InvalidArgument("emulator.bind_address is not an IPv4 address");
  }
  if (bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 ||
      listen(listen_fd_, 4) != 0) {
    return core::IoError("cannot listen on " + options_.bind_address + ":" +
                         std::to_string(options_.port) + ": " + std::strerror(errno));
  }
  socklen_t len = sizeof(addr);
  getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  thread_ = std::thread([this] { AcceptLoop(); });
  return core::OkStatus();
}

void ScannerEmulator::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (listen_fd_ >= 0) close(listen_fd_);
  listen_fd_ = -1;
}

void ScannerEmulator::AcceptLoop() {
  bool first = true;
  while (!stop_) {
    pollfd p{listen_fd_, POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) continue;
    TcpConnection client(fd);
    ++stats_.connections;
    Serve(client, first);
    first = false;
  }
}

void ScannerEmulator::RefuseWaitingClients() {
  while (true) {
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) return;
    ++stats_.refused_connections;  // counted before the client can see the close
    close(fd);
  }
}

bool ScannerEmulator::Producing(double now) const {
  return measuring_ && run_mode_ && now >= ready_s_;
}

bool ScannerEmulator::Reply(TcpConnection& client, const char* type, const char* name,
                            uint8_t value) {
  const ColaProtocol p = options_.protocol;
  return Send(client, FrameTelegram(p, drivers::sick::SmallReply(p, type, name, value)));
}

bool ScannerEmulator::Send(TcpConnection& client, const std::string& bytes) {
  const size_t piece = options_.max_write_bytes > 0 ? options_.max_write_bytes : bytes.size();
  for (size_t at = 0; at < bytes.size(); at += piece) {
    if (!client.WriteAll(std::string_view(bytes).substr(at, piece), kWriteTimeoutS).ok()) {
      return false;
    }
    if (piece < bytes.size()) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

bool ScannerEmulator::SendScan(TcpConnection& client, const char* type) {
  std::optional<drivers::sick::ScanTelegram> scan = source_->Next();
  if (!scan) return false;  // exhausted: hang up like a scanner switched off
  const uint64_t n = ++stats_.scans_sent;
  const ColaProtocol framing = options_.cola_b_scans ? ColaProtocol::kColaB : options_.protocol;
  std::string bytes = drivers::sick::FrameTelegram(
      framing, drivers::sick::EncodeScanTelegram(*scan, framing, type));
  if (options_.corrupt_every > 0 && n % options_.corrupt_every == 0) {
    if (framing == ColaProtocol::kColaB) {
      bytes.back() = static_cast<char>(bytes.back() ^ 0x5A);
    } else {
      bytes.resize(bytes.size() / 2);  // cut off, the next STX starts over
    }
  }
  if (options_.garbage_every > 0 && n % options_.garbage_every == 0) {
    bytes = std::string("\x02\x02garbage\x03\xff\x00\x02 noise", 20) + bytes;
  }
  return Send(client, bytes);
}

bool ScannerEmulator::HandleRequest(TcpConnection& client, const std::string& payload,
                                    Session& session) {
  ++stats_.requests;
  const ColaProtocol p = options_.protocol;
  core::Result<drivers::sick::ParsedCommand> c = drivers::sick::ParseCommand(payload, p);
  if (!c.ok()) return Send(client, FrameTelegram(p, drivers::sick::ErrorReply(p, 1)));
  const std::string& name = c->name;
  if (c->type == "sMN" && name == "SetAccessMode") {
    const bool ok = c->value == drivers::sick::kAuthorizedClientLevel &&
                    c->password == drivers::sick::kAuthorizedClientPasswordHash;
    session.logged_in |= ok;
    if (ok) {
      ++stats_.logins;
      run_mode_ = false;  // the configuration level: no scans until Run
    }
    return Reply(client, "sAN", "SetAccessMode", ok);
  }
  if (c->type == "sMN" && name == "Run") {
    ++stats_.run_requests;
    run_mode_ = true;
    return Reply(client, "sAN", "Run", 1);
  }
  if (c->type == "sRN" && name == "SCdevicestate") {
    const bool busy = measuring_ && MonotonicNowS() < ready_s_;
    return Reply(client, "sRA", "SCdevicestate", busy ? 0 : 1);
  }
  const bool measurement = c->type == "sMN" && (name == "LMCstartmeas" || name == "LMCstopmeas");
  const bool scan_request = name == "LMDscandata" && (c->type == "sEN" || c->type == "sRN");
  if (!measurement && !scan_request) {
    return Send(client, FrameTelegram(p, drivers::sick::ErrorReply(p, 2)));
  }
  if (options_.require_login && !session.logged_in) {
    return Send(client, FrameTelegram(p, drivers::sick::ErrorReply(p, 3)));
  }
  if (name == "LMCstartmeas") {
    ++stats_.start_requests;
    if (!measuring_) ready_s_ = MonotonicNowS() + options_.spin_up_s;
    measuring_ = true;
    return Reply(client, "sAN", "LMCstartmeas", 0);
  }
  if (name == "LMCstopmeas") {
    measuring_ = false;
    return Reply(client, "sAN", "LMCstopmeas", 0);
  }
  if (c->type == "sRN") {
    session.poll_pending = true;  // answered once the device measures
    return true;
  }
  session.streaming = c->value == 1;
  return Reply(client, "sEA", "LMDscandata", session.streaming);
}

void ScannerEmulator::Serve(TcpConnection& client, bool first) {
  drivers::sick::TelegramSplitterOptions splitter_options;
  splitter_options.protocol = options_.protocol;
  splitter_options.max_payload_bytes = 4096;
  drivers::sick::TelegramSplitter requests(splitter_options);
  Session session;
  size_t sent_here = 0;
  const double period_s = source_->period_s() / options_.speed_factor;
  double next_scan_s = MonotonicNowS();
  uint8_t buffer[4096];
  while (!stop_) {
    const bool silent =
        first && options_.silent_after_scans > 0 && sent_here >= options_.silent_after_scans;
    const double now = MonotonicNowS();
    const bool producing = Producing(now) && !silent;
    if (producing && session.poll_pending) {
      session.poll_pending = false;
      if (!SendScan(client, "sRA")) return;
      continue;
    }
    if (producing && session.streaming && now >= next_scan_s) {
      if (!SendScan(client, "sSN")) return;
      ++sent_here;
      next_scan_s = std::max(next_scan_s + period_s, now - period_s);
      continue;
    }
    const double wait = producing && session.streaming ? std::min(0.05, next_scan_s - now) : 0.05;
    core::Result<size_t> n = client.Read(buffer, sizeof(buffer), wait);
    if (!n.ok()) return;  // the client hung up
    RefuseWaitingClients();
    requests.Feed(buffer, *n);
    while (std::optional<std::string> payload = requests.Next()) {
      if (!HandleRequest(client, *payload, session)) return;
    }
  }
}

}  // namespace fleetmap::sim::sick
