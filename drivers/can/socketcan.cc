#include "drivers/can/socketcan.h"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

namespace fleetmap::drivers::can {
namespace {

core::Status Errno(const std::string& what) {
  return core::IoError(what + ": " + std::strerror(errno));
}

uint32_t ToKernelId(const CanFrame& f) {
  if (f.error) return f.id | CAN_ERR_FLAG;
  uint32_t id = f.id;
  if (f.extended) id |= CAN_EFF_FLAG;
  if (f.rtr) id |= CAN_RTR_FLAG;
  return id;
}

void FromKernel(const canfd_frame& k, bool is_fd, CanFrame& f) {
  f.error = k.can_id & CAN_ERR_FLAG;
  f.extended = !f.error && (k.can_id & CAN_EFF_FLAG);
  f.rtr = !f.error && (k.can_id & CAN_RTR_FLAG);
  f.id = k.can_id & (f.error ? CAN_ERR_MASK : (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK));
  f.fd = is_fd;
  f.fd_flags = is_fd ? (k.flags & (CANFD_BRS | CANFD_ESI)) : 0;
  f.len = std::min<uint8_t>(k.len, is_fd ? 64 : 8);
  const auto* classic = reinterpret_cast<const can_frame*>(&k);
  f.len8_dlc = !is_fd && classic->len == 8 && classic->len8_dlc > 8 ? classic->len8_dlc : 0;
  std::memcpy(f.data.data(), k.data, f.len);
}

core::Status SetOption(int fd, int level, int name, const void* value, socklen_t size,
                       const char* what) {
  if (setsockopt(fd, level, name, value, size) != 0) return Errno(what);
  return core::OkStatus();
}

core::Status Configure(int fd, const SocketCanOptions& o) {
  std::vector<can_filter> filters;
  for (const CanIdFilter& f : o.filters) {
    can_filter k;
    k.can_id = f.id | (f.extended ? CAN_EFF_FLAG : 0);
    k.can_mask = f.mask | CAN_EFF_FLAG | CAN_RTR_FLAG;
    k.can_mask &= ~CAN_RTR_FLAG;  // accept data and remote frames alike
    filters.push_back(k);
  }
  if (!filters.empty()) {
    FLEETMAP_RETURN_IF_ERROR(SetOption(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                                       static_cast<socklen_t>(filters.size() * sizeof(can_filter)),
                                       "CAN_RAW_FILTER"));
  }
  const can_err_mask_t errors = o.receive_error_frames ? CAN_ERR_MASK : 0;
  FLEETMAP_RETURN_IF_ERROR(SetOption(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof(errors),
                                     "CAN_RAW_ERR_FILTER"));
  const int own = o.receive_own_frames, on = 1;
  FLEETMAP_RETURN_IF_ERROR(SetOption(fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof(own),
                                     "CAN_RAW_RECV_OWN_MSGS"));
  if (o.enable_fd) {
    FLEETMAP_RETURN_IF_ERROR(
        SetOption(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof(on), "CAN_RAW_FD_FRAMES"));
  }
  FLEETMAP_RETURN_IF_ERROR(
      SetOption(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof(on), "SO_TIMESTAMPNS"));
  FLEETMAP_RETURN_IF_ERROR(SetOption(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof(on), "SO_RXQ_OVFL"));
  if (o.receive_buffer_bytes > 0) {
    // SO_RCVBUFFORCE passes net.core.rmem_max where we may (CAP_NET_ADMIN); else SO_RCVBUF.
    if (setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &o.receive_buffer_bytes, sizeof(int)) != 0) {
      FLEETMAP_RETURN_IF_ERROR(
          SetOption(fd, SOL_SOCKET, SO_RCVBUF, &o.receive_buffer_bytes, sizeof(int), "SO_RCVBUF"));
    }
  }
  return core::OkStatus();
}

}  // namespace

core::Status SocketCanOptions::Validate() const {
  if (interface.empty() || interface.size() >= IFNAMSIZ) {
    return core::InvalidArgument("socketcan.interface must have 1 to 15 characters");
  }
  if (receive_buffer_bytes < 0) {
    return core::InvalidArgument("socketcan.receive_buffer_bytes must be >= 0");
  }
  return core::OkStatus();
}

core::Result<SocketCan> SocketCan::Open(const SocketCanOptions& o) {
  FLEETMAP_RETURN_IF_ERROR(o.Validate());
  const int fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    if (errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT) {
      return core::Unimplemented("the kernel has no SocketCAN (AF_CAN): " +
                                 std::string(std::strerror(errno)));
    }
    return Errno("socket(PF_CAN)");
  }
  SocketCan socket_can(fd, o.interface, o.enable_fd);
  const unsigned index = if_nametoindex(o.interface.c_str());
  if (index == 0) return core::NotFound("no CAN interface named " + o.interface);
  FLEETMAP_RETURN_IF_ERROR(Configure(fd, o));
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    return Errno("bind to " + o.interface);
  }
  return socket_can;
}

SocketCan::SocketCan(SocketCan&& other) noexcept
    : fd_(other.fd_),
      interface_(std::move(other.interface_)),
      fd_enabled_(other.fd_enabled_),
      stats_(other.stats_),
      last_drop_counter_(other.last_drop_counter_) {
  other.fd_ = -1;
}

SocketCan::~SocketCan() {
  if (fd_ >= 0) close(fd_);
}

core::Result<bool> SocketCan::WaitReadable(double timeout_s) {
  pollfd p{fd_, POLLIN, 0};
  const int ms = timeout_s > 0 ? static_cast<int>(std::ceil(timeout_s * 1000.0)) : 0;
  const int r = poll(&p, 1, ms);
  if (r < 0 && errno != EINTR) return Errno("poll");
  return r > 0;
}

core::Result<bool> SocketCan::ReadOne(CanFrame& frame) {
  canfd_frame k{};
  iovec iov{&k, sizeof(k)};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(uint32_t))];
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof(control);
  const ssize_t n = recvmsg(fd_, &msg, MSG_DONTWAIT);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return false;
    return Errno("recvmsg on " + interface_);
  }
  if (n != CAN_MTU && n != CANFD_MTU) {
    ++stats_.truncated;
    return false;
  }
  FromKernel(k, n == CANFD_MTU, frame);
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level != SOL_SOCKET) continue;
    if (c->cmsg_type == SO_TIMESTAMPNS) {
      timespec ts;
      std::memcpy(&ts, CMSG_DATA(c), sizeof(ts));
      frame.stamp_s = static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
    } else if (c->cmsg_type == SO_RXQ_OVFL) {
      uint32_t drops;
      std::memcpy(&drops, CMSG_DATA(c), sizeof(drops));
      stats_.kernel_drops += drops - last_drop_counter_;
      last_drop_counter_ = drops;
    }
  }
  return true;
}

core::Result<size_t> SocketCan::ReadAvailable(std::vector<CanFrame>& out, size_t max_frames) {
  size_t count = 0;
  CanFrame frame;
  while (count < max_frames) {
    core::Result<bool> got = ReadOne(frame);
    if (!got.ok()) return got.status();
    if (!*got) break;
    frame.error ? ++stats_.error_frames : ++stats_.frames;
    out.push_back(frame);
    ++count;
  }
  return count;
}

core::Status SocketCan::Write(const CanFrame& frame) {
  FLEETMAP_RETURN_IF_ERROR(frame.Validate());
  if (frame.fd && !fd_enabled_) return core::FailedPrecondition("CAN FD is not enabled");
  canfd_frame k{};
  k.can_id = ToKernelId(frame);
  k.len = frame.len;
  if (frame.fd) {
    k.flags = frame.fd_flags | CANFD_FDF;
  } else {
    reinterpret_cast<can_frame*>(&k)->len8_dlc = frame.len8_dlc;
  }
  std::memcpy(k.data, frame.data.data(), frame.len);
  const size_t size = frame.fd ? CANFD_MTU : CAN_MTU;
  const ssize_t n = write(fd_, &k, size);
  if (n != static_cast<ssize_t>(size)) return Errno("write to " + interface_);
  return core::OkStatus();
}

}  // namespace fleetmap::drivers::can
