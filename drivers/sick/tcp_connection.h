// A TCP connection with timeouts on connect, read and write (non-blocking socket and poll),
// closed when destroyed. The SICK client and the emulator's tests use it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/result.h"

namespace fleetmap::drivers::sick {

class TcpConnection {
 public:
  // Resolves `host` (name or address) and connects within `timeout_s` (IoError otherwise).
  static core::Result<TcpConnection> Connect(const std::string& host, int port, double timeout_s);
  // Takes ownership of a connected socket (from accept).
  explicit TcpConnection(int fd) : fd_(fd) {}
  TcpConnection(TcpConnection&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  TcpConnection& operator=(TcpConnection&& other) noexcept;
  TcpConnection(const TcpConnection&) = delete;
  TcpConnection& operator=(const TcpConnection&) = delete;
  ~TcpConnection() { Close(); }

  // Waits up to `timeout_s` for bytes and reads at most `capacity`. Returns 0 on timeout;
  // IoError when the peer closed the connection or the socket failed.
  core::Result<size_t> Read(uint8_t* buffer, size_t capacity, double timeout_s);
  // Writes everything within `timeout_s` (IoError otherwise).
  core::Status WriteAll(std::string_view bytes, double timeout_s);
  void Close();
  bool is_open() const { return fd_ >= 0; }
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

// Milliseconds for poll(): rounds up so that a positive timeout never becomes 0.
int PollTimeoutMs(double timeout_s);

// Seconds of the monotonic clock, for the timeouts of the driver and its emulator.
double MonotonicNowS();

}  // namespace fleetmap::drivers::sick
