// A raw SocketCAN socket (Linux AF_CAN, CAN_RAW) on one interface (vcan0, can0), as the plant and controller
// processes use it (docs/can.md):
//   - non-blocking socket; receive waits in ppoll until a CLOCK_MONOTONIC deadline, send retries a full queue
//     (EAGAIN / ENOBUFS) until its deadline;
//   - CAN FD enabled (CAN_RAW_FD_FRAMES) and required of the interface (MTU 72: `ip link set vcan0 mtu 72`);
//   - CAN_RAW_FILTER: only the 11-bit identifiers this end receives (a flood of other traffic stays in the
//     kernel), any frame type on them, so a classic or remote frame on one of our ids reaches the decoder
//     and is counted; an empty id list receives everything (diagnosis, tests);
//   - CAN_RAW_ERR_FILTER = CAN_ERR_MASK: error frames of the controller are received and counted;
//   - SO_TIMESTAMPNS: every frame carries the kernel's receive time (CLOCK_REALTIME);
//   - SO_RXQ_OVFL: frames the kernel dropped because our receive queue was full are counted.
// Where the kernel has no AF_CAN, open() fails with a message that says so (EAFNOSUPPORT; hil/vcan-run boots
// a VM instead). No heap after open(); recvmsg/write on stack buffers.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hil/can/can_frame.hpp"

namespace gyrostab::can {

struct SocketCanConfig {
  std::string ifname{"vcan0"};
  std::vector<std::uint32_t> receive_ids;  // 11-bit ids to receive (empty: every frame)
  bool error_frames{true};                 // receive error frames
  bool timestamps{true};                   // kernel receive timestamps
  int receive_buffer_bytes{1 << 20};       // SO_RCVBUF request (0: kernel default)
};

struct SocketCanCounters {
  std::uint64_t sent{0};             // frames written [-]
  std::uint64_t send_retries{0};     // writes retried on a full queue (EAGAIN / ENOBUFS) [-]
  std::uint64_t send_failures{0};    // frames given up at their deadline or refused [-]
  std::uint64_t received{0};         // frames read (any kind) [-]
  std::uint64_t error_frames{0};     // of which error frames [-]
  std::uint64_t kernel_drops{0};     // frames the kernel dropped for a full receive queue (SO_RXQ_OVFL) [-]
  std::uint64_t odd_reads{0};        // reads of neither CAN_MTU nor CANFD_MTU bytes (ignored) [-]
};

enum class CanRx { kFrame, kTimeout, kInterrupted, kError };

class SocketCan {
 public:
  SocketCan() = default;
  ~SocketCan();
  SocketCan(const SocketCan&) = delete;
  SocketCan& operator=(const SocketCan&) = delete;
  SocketCan(SocketCan&& o) noexcept
      : fd_(o.fd_), last_drop_count_(o.last_drop_count_), counters_(o.counters_), last_error_(std::move(o.last_error_)) {
    o.fd_ = -1;
  }

  // Start-up (allocates nothing after it returns). false with `error` (which call failed and why).
  bool open(const SocketCanConfig& config, std::string& error);
  void close();
  bool is_open() const { return fd_ >= 0; }

  // Writes one frame; a full queue is retried until deadline_ns (CLOCK_MONOTONIC). false: not sent.
  bool send(const CanFrame& f, std::int64_t deadline_ns);
  // Reads the next frame, waiting until deadline_ns (CLOCK_MONOTONIC; INT64_MAX: no deadline).
  CanRx receive(CanFrame& out, std::int64_t deadline_ns);

  const SocketCanCounters& counters() const { return counters_; }
  const std::string& last_error() const { return last_error_; }
  int fd() const { return fd_; }

 private:
  int fd_{-1};
  std::uint32_t last_drop_count_{0};
  SocketCanCounters counters_{};
  std::string last_error_;
};

// True if this kernel can open an AF_CAN raw socket (false: no CAN support, e.g. EAFNOSUPPORT).
bool socketcan_available(std::string* why = nullptr);

}  // namespace gyrostab::can
