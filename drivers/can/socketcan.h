// A SocketCAN raw socket (Linux AF_CAN): bound to an interface by name, with receive filters,
// kernel receive timestamps (SO_TIMESTAMPNS, CLOCK_REALTIME), the kernel's count of frames it
// dropped for us (SO_RXQ_OVFL), error frames, and optionally CAN FD. Reads never block: a
// caller waits with WaitReadable and then drains everything queued.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"
#include "drivers/can/can_frame.h"

namespace fleetmap::drivers::can {

// Accept a frame when (frame_id & mask) == (id & mask), as struct can_filter does.
struct CanIdFilter {
  uint32_t id = 0;
  uint32_t mask = 0;
  bool extended = false;  // match extended ids only (else standard ids only)
};

struct SocketCanOptions {
  std::string interface = "can0";
  std::vector<CanIdFilter> filters;  // empty: every frame
  bool receive_error_frames = true;  // count bus errors (CAN_RAW_ERR_FILTER all classes)
  bool receive_own_frames = false;   // CAN_RAW_RECV_OWN_MSGS
  bool enable_fd = false;            // CAN_RAW_FD_FRAMES
  int receive_buffer_bytes = 0;      // SO_RCVBUF(FORCE), bytes; 0: kernel default
  core::Status Validate() const;
};

struct SocketCanStats {
  uint64_t frames = 0;        // data and remote frames returned
  uint64_t error_frames = 0;  // error frames returned (not counted in `frames`)
  uint64_t kernel_drops = 0;  // frames the kernel dropped because our queue was full
  uint64_t truncated = 0;     // reads of an unexpected size
};

class SocketCan {
 public:
  // NotFound for an unknown interface; Unimplemented where the kernel has no AF_CAN.
  static core::Result<SocketCan> Open(const SocketCanOptions& options);
  SocketCan(SocketCan&& other) noexcept;
  SocketCan& operator=(SocketCan&&) = delete;
  SocketCan(const SocketCan&) = delete;
  ~SocketCan();

  // Waits up to `timeout_s` for a frame to be readable.
  core::Result<bool> WaitReadable(double timeout_s);
  // Appends every queued frame (at most `max_frames`) to `out` without blocking, each with
  // its kernel receive timestamp; returns how many were appended.
  core::Result<size_t> ReadAvailable(std::vector<CanFrame>& out, size_t max_frames = 1024);
  core::Status Write(const CanFrame& frame);

  const SocketCanStats& stats() const { return stats_; }
  const std::string& interface() const { return interface_; }

 private:
  SocketCan(int fd, std::string interface, bool fd_enabled)
      : fd_(fd), interface_(std::move(interface)), fd_enabled_(fd_enabled) {}
  core::Result<bool> ReadOne(CanFrame& frame);

  int fd_ = -1;
  std::string interface_;
  bool fd_enabled_ = false;
  SocketCanStats stats_;
  uint32_t last_drop_counter_ = 0;
};

}  // namespace fleetmap::drivers::can
