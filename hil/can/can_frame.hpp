// One CAN or CAN FD frame as the codec, the logs and the SocketCAN link see it: the fields of Linux's
// struct canfd_frame (id, length, flags, up to 64 data bytes) plus the receive timestamp, without including
// <linux/can.h>, so the codec and its fuzz target build anywhere (the link converts, socketcan_link.cpp).
// Plain data, fixed size, no heap.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gyrostab::can {

inline constexpr std::size_t kClassicMaxData = 8;
inline constexpr std::size_t kFdMaxData = 64;

// Frame kind and CAN FD flag bits (CanFrame::flags).
enum CanFlag : std::uint8_t {
  kFlagFd = 1u << 0,        // CAN FD frame (FDF): length up to 64, one of the FD lengths
  kFlagBrs = 1u << 1,       // FD bit-rate switch: data phase at the data bit rate
  kFlagEsi = 1u << 2,       // FD error-state indicator of the sender
  kFlagExtended = 1u << 3,  // 29-bit identifier
  kFlagRemote = 1u << 4,    // remote transmission request (classic only)
  kFlagError = 1u << 5,     // error frame reported by the controller / kernel (id = error class bits)
};

struct CanFrame {
  std::uint32_t id{0};     // 11-bit identifier (29-bit with kFlagExtended; error class with kFlagError)
  std::uint8_t len{0};     // data length in bytes: 0..8 classic, an FD length (fd_length_valid) for FD
  std::uint8_t flags{0};   // CanFlag set
  std::uint8_t data[kFdMaxData]{};
  std::int64_t time_ns{0};  // receive time (kernel timestamp, CLOCK_REALTIME) or log time; 0 when unknown [ns]

  constexpr bool fd() const { return (flags & kFlagFd) != 0; }
};

// The data lengths a CAN FD frame can have (DLC 0..15 → 0..8, 12, 16, 20, 24, 32, 48, 64).
constexpr bool fd_length_valid(std::size_t n) {
  return n <= 8 || n == 12 || n == 16 || n == 20 || n == 24 || n == 32 || n == 48 || n == 64;
}
// The DLC code of an FD length (fd_length_valid(n) must hold).
constexpr std::uint8_t fd_dlc(std::size_t n) {
  if (n <= 8) return static_cast<std::uint8_t>(n);
  switch (n) {
    case 12: return 9;
    case 16: return 10;
    case 20: return 11;
    case 24: return 12;
    case 32: return 13;
    case 48: return 14;
    default: return 15;
  }
}
// The smallest FD length that holds n bytes (n ≤ 64).
constexpr std::uint8_t fd_round_up(std::size_t n) {
  constexpr std::uint8_t kLengths[] = {12, 16, 20, 24, 32, 48, 64};
  if (n <= 8) return static_cast<std::uint8_t>(n);
  for (std::uint8_t l : kLengths)
    if (n <= l) return l;
  return 64;
}

}  // namespace gyrostab::can
