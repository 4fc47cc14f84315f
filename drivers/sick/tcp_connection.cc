#include "drivers/sick/tcp_connection.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

namespace fleetmap::drivers::sick {
namespace {

core::Status Errno(const std::string& what) {
  return core::IoError(what + ": " + std::strerror(errno));
}

// Waits for `events` on fd; false on timeout.
core::Result<bool> WaitFor(int fd, short events, double timeout_s) {
  pollfd p{fd, events, 0};
  int r;
  do {
    r = poll(&p, 1, PollTimeoutMs(timeout_s));
  } while (r < 0 && errno == EINTR);
  if (r < 0) return Errno("poll");
  return r > 0;
}

core::Status ConnectOne(int fd, const addrinfo* ai, double timeout_s) {
  if (connect(fd, ai->ai_addr, ai->ai_addrlen) == 0) return core::OkStatus();
  if (errno != EINPROGRESS) return Errno("connect");
  core::Result<bool> ready = WaitFor(fd, POLLOUT, timeout_s);
  if (!ready.ok()) return ready.status();
  if (!*ready) return core::IoError("connect: timed out");
  int error = 0;
  socklen_t len = sizeof(error);
  getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &len);
  if (error != 0) return core::IoError(std::string("connect: ") + std::strerror(error));
  return core::OkStatus();
}

}  // namespace

double MonotonicNowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int PollTimeoutMs(double timeout_s) {
  if (!(timeout_s > 0.0)) return 0;
  return static_cast<int>(std::min(std::ceil(timeout_s * 1000.0), 2.0e9));
}

core::Result<TcpConnection> TcpConnection::Connect(const std::string& host, int port,
                                                   double timeout_s) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* list = nullptr;
  const std::string service = std::to_string(port);
  if (const int e = getaddrinfo(host.c_str(), service.c_str(), &hints, &list); e != 0) {
    return core::IoError("cannot resolve " + host + ": " + gai_strerror(e));
  }
  core::Status last = core::IoError("no address for " + host);
  for (const addrinfo* ai = list; ai != nullptr; ai = ai->ai_next) {
    const int fd = socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) continue;
    last = ConnectOne(fd, ai, timeout_s);
    if (last.ok()) {
      freeaddrinfo(list);
      const int one = 1;
      setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
      return TcpConnection(fd);
    }
    close(fd);
  }
  freeaddrinfo(list);
  return last.WithContext(host + ":" + service);
}

TcpConnection& TcpConnection::operator=(TcpConnection&& other) noexcept {
  if (this != &other) {
    Close();
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

void TcpConnection::Close() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

core::Result<size_t> TcpConnection::Read(uint8_t* buffer, size_t capacity, double timeout_s) {
  if (fd_ < 0) return core::IoError("read on a closed connection");
  core::Result<bool> ready = WaitFor(fd_, POLLIN, timeout_s);
  if (!ready.ok()) return ready.status();
  if (!*ready) return size_t{0};
  ssize_t n;
  do {
    n = recv(fd_, buffer, capacity, 0);
  } while (n < 0 && errno == EINTR);
  if (n == 0) return core::IoError("connection closed by peer");
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK) return size_t{0};
    return Errno("recv");
  }
  return static_cast<size_t>(n);
}

core::Status TcpConnection::WriteAll(std::string_view bytes, double timeout_s) {
  size_t done = 0;
  while (done < bytes.size()) {
    if (fd_ < 0) return core::IoError("write on a closed connection");
    const ssize_t n = send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n > 0) {
      done += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return Errno("send");
    core::Result<bool> ready = WaitFor(fd_, POLLOUT, timeout_s);
    if (!ready.ok()) return ready.status();
    if (!*ready) return core::IoError("send: timed out");
  }
  return core::OkStatus();
}

}  // namespace fleetmap::drivers::sick
