#include "hil/can/socketcan_link.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>

namespace gyrostab::can {
namespace {

std::int64_t monotonic_now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::string errno_text(const char* what) {
  return std::string(what) + ": " + std::strerror(errno);
}

// Waits for `events` on fd until deadline_ns. 1: ready, 0: deadline, -1: interrupted, -2: error.
int wait_fd(int fd, short events, std::int64_t deadline_ns) {
  pollfd p{fd, events, 0};
  timespec ts{};
  timespec* timeout = nullptr;
  if (deadline_ns != std::numeric_limits<std::int64_t>::max()) {
    const std::int64_t left = deadline_ns - monotonic_now_ns();
    if (left <= 0) return 0;
    ts.tv_sec = static_cast<time_t>(left / 1'000'000'000);
    ts.tv_nsec = static_cast<long>(left % 1'000'000'000);
    timeout = &ts;
  }
  const int r = ppoll(&p, 1, timeout, nullptr);
  if (r > 0) return 1;
  if (r == 0) return 0;
  return errno == EINTR ? -1 : -2;
}

}  // namespace

bool socketcan_available(std::string* why) {
  const int s = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (s < 0) {
    if (why != nullptr) *why = errno_text("socket(AF_CAN, SOCK_RAW, CAN_RAW)");
    return false;
  }
  ::close(s);
  return true;
}

SocketCan::~SocketCan() {
  close();
}

void SocketCan::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool SocketCan::open(const SocketCanConfig& config, std::string& error) {
  close();
  if (config.ifname.empty() || config.ifname.size() >= IFNAMSIZ) {
    error = "CAN interface name '" + config.ifname + "' must have 1 to " + std::to_string(IFNAMSIZ - 1) + " characters";
    return false;
  }
  const int s = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (s < 0) {
    error = errno_text("socket(AF_CAN, SOCK_RAW, CAN_RAW)");
    if (errno == EAFNOSUPPORT) error += " (this kernel has no CAN support: run through hil/vcan-run, docs/can.md)";
    return false;
  }
  fd_ = s;
  ifreq ifr{};
  std::memcpy(ifr.ifr_name, config.ifname.c_str(), config.ifname.size() + 1);
  if (::ioctl(s, SIOCGIFINDEX, &ifr) < 0) {
    error = errno_text(("CAN interface " + config.ifname).c_str());
    close();
    return false;
  }
  const int ifindex = ifr.ifr_ifindex;
  if (::ioctl(s, SIOCGIFMTU, &ifr) < 0) {
    error = errno_text(("MTU of " + config.ifname).c_str());
    close();
    return false;
  }
  if (ifr.ifr_mtu != static_cast<int>(CANFD_MTU)) {
    error = "CAN interface " + config.ifname + " is not CAN FD capable (MTU " + std::to_string(ifr.ifr_mtu) +
            "; CAN FD needs " + std::to_string(CANFD_MTU) + ": ip link set " + config.ifname + " mtu 72)";
    close();
    return false;
  }
  const int on = 1;
  if (::setsockopt(s, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on) < 0) {
    error = errno_text("setsockopt(CAN_RAW_FD_FRAMES)");
    close();
    return false;
  }
  if (!config.receive_ids.empty()) {
    std::vector<can_filter> filters;
    for (std::uint32_t id : config.receive_ids) {
      // Standard (11-bit) frames with exactly this id, data or remote: EFF frames never match.
      filters.push_back(can_filter{id & CAN_SFF_MASK, CAN_EFF_FLAG | CAN_SFF_MASK});
    }
    if (::setsockopt(s, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                     static_cast<socklen_t>(filters.size() * sizeof(can_filter))) < 0) {
      error = errno_text("setsockopt(CAN_RAW_FILTER)");
      close();
      return false;
    }
  }
  if (config.error_frames) {
    const can_err_mask_t mask = CAN_ERR_MASK;
    if (::setsockopt(s, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof mask) < 0) {
      error = errno_text("setsockopt(CAN_RAW_ERR_FILTER)");
      close();
      return false;
    }
  }
  if (config.timestamps && ::setsockopt(s, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on) < 0) {
    error = errno_text("setsockopt(SO_TIMESTAMPNS)");
    close();
    return false;
  }
  if (::setsockopt(s, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) < 0) {
    error = errno_text("setsockopt(SO_RXQ_OVFL)");
    close();
    return false;
  }
  if (config.receive_buffer_bytes > 0) {
    // A process with CAP_NET_ADMIN (root, as in the test VM) gets the size it asks for (SO_RCVBUFFORCE);
    // otherwise it is a request that the kernel caps at net.core.rmem_max (212 992 bytes by default, a few
    // hundred FD frames: a slow receiver lost frames to a canplayer burst). The kernel doubles it for
    // bookkeeping. Not fatal.
    if (::setsockopt(s, SOL_SOCKET, SO_RCVBUFFORCE, &config.receive_buffer_bytes,
                     sizeof config.receive_buffer_bytes) < 0) {
      ::setsockopt(s, SOL_SOCKET, SO_RCVBUF, &config.receive_buffer_bytes, sizeof config.receive_buffer_bytes);
    }
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifindex;
  if (::bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) {
    error = errno_text(("bind to " + config.ifname).c_str());
    close();
    return false;
  }
  return true;
}

bool SocketCan::send(const CanFrame& f, std::int64_t deadline_ns) {
  if (fd_ < 0) return false;
  canfd_frame frame{};
  canid_t id = f.id;
  if ((f.flags & kFlagError) != 0) {
    id = (id & CAN_ERR_MASK) | CAN_ERR_FLAG;
  } else if ((f.flags & kFlagExtended) != 0) {
    id = (id & CAN_EFF_MASK) | CAN_EFF_FLAG;
  } else {
    id &= CAN_SFF_MASK;
  }
  if ((f.flags & kFlagRemote) != 0) id |= CAN_RTR_FLAG;
  frame.can_id = id;
  std::size_t size = CAN_MTU;
  if (f.fd()) {
    frame.len = f.len > CANFD_MAX_DLEN ? CANFD_MAX_DLEN : f.len;
    frame.flags = static_cast<std::uint8_t>(((f.flags & kFlagBrs) != 0 ? CANFD_BRS : 0) |
                                            ((f.flags & kFlagEsi) != 0 ? CANFD_ESI : 0));
    std::memcpy(frame.data, f.data, frame.len);
    size = CANFD_MTU;
  } else {
    // struct can_frame is a prefix of canfd_frame with the same layout for id, length and 8 data bytes.
    frame.len = f.len > CAN_MAX_DLEN ? CAN_MAX_DLEN : f.len;
    std::memcpy(frame.data, f.data, frame.len);
  }
  for (;;) {
    const ssize_t n = ::write(fd_, &frame, size);
    if (n == static_cast<ssize_t>(size)) {
      ++counters_.sent;
      return true;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS || errno == EINTR)) {
      ++counters_.send_retries;
      // ENOBUFS does not always wake poll: wait a little, bounded by the deadline.
      const std::int64_t now = monotonic_now_ns();
      if (now >= deadline_ns) break;
      const int r = wait_fd(fd_, POLLOUT, now + 100'000 < deadline_ns ? now + 100'000 : deadline_ns);
      if (r == -2) break;
      if (r == 0) {
        timespec nap{0, 50'000};
        nanosleep(&nap, nullptr);
      }
      continue;
    }
    last_error_ = n < 0 ? errno_text("write to the CAN socket") : "short write to the CAN socket";
    break;
  }
  ++counters_.send_failures;
  return false;
}

CanRx SocketCan::receive(CanFrame& out, std::int64_t deadline_ns) {
  if (fd_ < 0) return CanRx::kError;
  for (;;) {
    canfd_frame frame{};
    iovec iov{&frame, sizeof frame};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(std::uint32_t)) + 64];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) {
        const int r = wait_fd(fd_, POLLIN, deadline_ns);
        if (r == 1) continue;
        if (r == 0) return CanRx::kTimeout;
        if (r == -1) return CanRx::kInterrupted;
        last_error_ = errno_text("ppoll on the CAN socket");
        return CanRx::kError;
      }
      if (errno == EINTR) return CanRx::kInterrupted;
      last_error_ = errno_text("recvmsg from the CAN socket");
      return CanRx::kError;
    }
    out = CanFrame{};
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SCM_TIMESTAMPNS) {
        timespec ts{};
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        out.time_ns = static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
      } else if (c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t drops = 0;
        std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
        // The kernel reports its running total for this socket.
        counters_.kernel_drops += static_cast<std::uint32_t>(drops - last_drop_count_);
        last_drop_count_ = drops;
      }
    }
    if (n != static_cast<ssize_t>(CAN_MTU) && n != static_cast<ssize_t>(CANFD_MTU)) {
      ++counters_.odd_reads;
      continue;
    }
    ++counters_.received;
    const canid_t id = frame.can_id;
    if ((id & CAN_ERR_FLAG) != 0) {
      out.flags |= kFlagError;
      out.id = id & CAN_ERR_MASK;
      ++counters_.error_frames;
    } else if ((id & CAN_EFF_FLAG) != 0) {
      out.flags |= kFlagExtended;
      out.id = id & CAN_EFF_MASK;
    } else {
      out.id = id & CAN_SFF_MASK;
    }
    if ((id & CAN_RTR_FLAG) != 0) out.flags |= kFlagRemote;
    if (n == static_cast<ssize_t>(CANFD_MTU)) {
      out.flags |= kFlagFd;
      if ((frame.flags & CANFD_BRS) != 0) out.flags |= kFlagBrs;
      if ((frame.flags & CANFD_ESI) != 0) out.flags |= kFlagEsi;
      out.len = frame.len > CANFD_MAX_DLEN ? CANFD_MAX_DLEN : frame.len;
    } else {
      out.len = frame.len > CAN_MAX_DLEN ? CAN_MAX_DLEN : frame.len;
    }
    std::memcpy(out.data, frame.data, out.len);
    return CanRx::kFrame;
  }
}

}  // namespace gyrostab::can
