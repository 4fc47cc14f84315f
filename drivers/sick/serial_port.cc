#include "drivers/sick/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "drivers/sick/tcp_connection.h"

namespace fleetmap::drivers::sick {
namespace {

core::Result<speed_t> BaudConstant(int baud) {
  switch (baud) {
    case 9600:
      return speed_t{B9600};
    case 19200:
      return speed_t{B19200};
    case 38400:
      return speed_t{B38400};
    case 57600:
      return speed_t{B57600};
    case 115200:
      return speed_t{B115200};
    case 230400:
      return speed_t{B230400};
    case 460800:
      return speed_t{B460800};
    case 500000:
      return speed_t{B500000};
    case 921600:
      return speed_t{B921600};
    default:
      return core::InvalidArgument("unsupported baud rate " + std::to_string(baud));
  }
}

}  // namespace

core::Result<SerialPort> SerialPort::Open(const std::string& path, int baud) {
  core::Result<speed_t> speed = BaudConstant(baud);
  if (!speed.ok()) return speed.status();
  const int fd = open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return core::IoError("cannot open " + path + ": " + std::strerror(errno));
  SerialPort port(fd);
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    return core::IoError(path + " is not a terminal: " + std::strerror(errno));
  }
  cfmakeraw(&tio);
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS);
  tio.c_cflag |= CLOCAL | CREAD | CS8;
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (cfsetispeed(&tio, *speed) != 0 || cfsetospeed(&tio, *speed) != 0 ||
      tcsetattr(fd, TCSANOW, &tio) != 0) {
    return core::IoError("cannot configure " + path + ": " + std::strerror(errno));
  }
  tcflush(fd, TCIFLUSH);
  return port;
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) close(fd_);
}

core::Result<size_t> SerialPort::Read(uint8_t* buffer, size_t capacity, double timeout_s) {
  pollfd p{fd_, POLLIN, 0};
  const int r = poll(&p, 1, PollTimeoutMs(timeout_s));
  if (r < 0 && errno != EINTR) return core::IoError(std::string("poll: ") + std::strerror(errno));
  if (r <= 0) return size_t{0};
  const ssize_t n = read(fd_, buffer, capacity);
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) return size_t{0};
    return core::IoError(std::string("serial read: ") + std::strerror(errno));
  }
  if (n == 0 && (p.revents & POLLHUP)) return core::IoError("serial port hung up");
  return static_cast<size_t>(n);
}

core::Result<S300Telegram> S300SerialReader::Next(double timeout_s) {
  const double deadline = MonotonicNowS() + timeout_s;
  uint8_t buffer[4096];
  while (true) {
    if (std::optional<S300Telegram> t = splitter_.Next()) return std::move(*t);
    const double left = deadline - MonotonicNowS();
    if (left <= 0.0) return core::IoError("no S300 telegram within the timeout");
    core::Result<size_t> n = port_.Read(buffer, sizeof(buffer), left);
    if (!n.ok()) return n.status();
    splitter_.Feed(buffer, *n);
  }
}

}  // namespace fleetmap::drivers::sick
