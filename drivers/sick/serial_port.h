// A serial port in raw mode (termios: 8 data bits, no parity, one stop bit, no flow control)
// for the S300's RS-422 output (500 kBaud by default) through a USB adapter, and the reader
// that turns its bytes into S300 telegrams. Works on pseudo-terminals too, which the tests use.
#pragma once

#include <string>

#include "core/result.h"
#include "drivers/sick/s300_telegram.h"

namespace fleetmap::drivers::sick {

class SerialPort {
 public:
  // Opens `path` and configures it; baud rates from 9600 to 921600 (InvalidArgument else).
  static core::Result<SerialPort> Open(const std::string& path, int baud);
  SerialPort(SerialPort&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  SerialPort& operator=(SerialPort&&) = delete;
  SerialPort(const SerialPort&) = delete;
  ~SerialPort();

  // Waits up to `timeout_s`; returns the bytes read (0 on timeout) or IoError.
  core::Result<size_t> Read(uint8_t* buffer, size_t capacity, double timeout_s);
  int fd() const { return fd_; }

 private:
  explicit SerialPort(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// Reads S300 telegrams from a serial port.
class S300SerialReader {
 public:
  explicit S300SerialReader(SerialPort port) : port_(std::move(port)) {}
  // The next telegram within `timeout_s` (IoError on timeout or a port error).
  core::Result<S300Telegram> Next(double timeout_s);
  const S300SplitterStats& stats() const { return splitter_.stats(); }

 private:
  SerialPort port_;
  S300StreamSplitter splitter_;
};

}  // namespace fleetmap::drivers::sick
