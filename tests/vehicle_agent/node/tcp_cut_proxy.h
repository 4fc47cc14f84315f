// A TCP forwarder on loopback between the agent and the scanner emulator, whose connection a
// test can cut (both sides closed, new connections refused: a pulled cable or a scanner
// reboot as the agent sees it) and restore, while the scanner itself keeps running.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace fleetmap::vehicle_agent::node::testing {

class TcpCutProxy {
 public:
  explicit TcpCutProxy(int upstream_port) : upstream_port_(upstream_port) {
    Listen(0);
    thread_ = std::thread([this] { Run(); });
  }
  ~TcpCutProxy() {
    stop_ = true;
    thread_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    CloseAll();
    if (listen_fd_ >= 0) close(listen_fd_);
  }
  int port() const { return port_; }
  // Closes the connection on both sides and refuses new ones until Restore.
  void Cut() {
    std::lock_guard<std::mutex> lock(mutex_);
    CloseAll();
    close(listen_fd_);
    listen_fd_ = -1;
  }
  void Restore() {
    std::lock_guard<std::mutex> lock(mutex_);
    Listen(port_);
  }

 private:
  void Listen(int port) {
    listen_fd_ = socket(AF_INET, SOCK_STREAM, 0);
    const int one = 1;
    setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<uint16_t>(port));
    if (bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        listen(listen_fd_, 4) != 0)
      throw std::runtime_error("proxy: cannot listen");
    socklen_t len = sizeof a;
    getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  int ConnectUpstream() const {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<uint16_t>(upstream_port_));
    if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      close(fd);
      return -1;
    }
    return fd;
  }
  void CloseAll() {
    for (int fd : fds_) close(fd);
    fds_.clear();
  }
  void Run() {
    char buffer[65536];
    while (!stop_) {
      std::unique_lock<std::mutex> lock(mutex_);
      std::vector<pollfd> p;
      if (listen_fd_ >= 0) p.push_back({listen_fd_, POLLIN, 0});
      for (int fd : fds_) p.push_back({fd, POLLIN, 0});
      lock.unlock();
      poll(p.data(), p.size(), 10);
      lock.lock();
      for (const pollfd& q : p) {
        if (!(q.revents & (POLLIN | POLLHUP | POLLERR))) continue;
        if (q.fd == listen_fd_) {
          const int client = accept(listen_fd_, nullptr, nullptr);
          const int upstream = client >= 0 ? ConnectUpstream() : -1;
          if (upstream < 0) {
            if (client >= 0) close(client);
            continue;
          }
          fds_ = {client, upstream};  // one connection at a time, as a scanner allows
          continue;
        }
        if (fds_.size() != 2 || (q.fd != fds_[0] && q.fd != fds_[1])) continue;  // cut meanwhile
        const int other = q.fd == fds_[0] ? fds_[1] : fds_[0];
        const ssize_t n = read(q.fd, buffer, sizeof buffer);
        if (n <= 0 || write(other, buffer, static_cast<size_t>(n)) != n) {
          CloseAll();
          break;
        }
      }
    }
  }

  const int upstream_port_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::vector<int> fds_;
  std::mutex mutex_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace fleetmap::vehicle_agent::node::testing
