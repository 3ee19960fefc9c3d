// Bus load of the CAN FD bus of a device (frame_map.hpp DeviceBus: the frames of its map) at its tick rate, and the 70 % limit above which a
// scene is refused for CAN (docs/can.md). Worst-case bit stuffing, as CAN tools quote it (canbusload's
// default): what the bus must be able to carry whatever the data.
//
// Bits of a frame with n data bytes (ISO 11898-1:2015), 11-bit identifier:
//   classic:  SOF ID RTR IDE r0 DLC data CRC15 = 34 + 8n stuffable bits, worst case one stuff bit per 4 after
//             the first: floor((33 + 8n)/4); then CRC delimiter, ACK slot and delimiter, EOF 7, IFS 3 = 13.
//             n = 8: 135 bits.
//   CAN FD:   arbitration phase (nominal rate): SOF ID RRS IDE FDF res BRS = 17 bits + 4 stuff bits, and after
//             the data phase ACK slot, ACK delimiter, EOF 7, IFS 3 = 12 bits: 33 bits.
//             data phase (data rate when BRS): ESI DLC data = 5 + 8n bits, their dynamic stuff bits
//             floor((21 + 8n)/4) − 4, stuff count 4, CRC 17 (n ≤ 16) or 21, fixed stuff bits 6 or 7, CRC
//             delimiter 1. n = 64: 679 bits.
// O(1) per frame; no heap.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hil/can/frame_map.hpp"

namespace gyrostab::can {

inline constexpr double kMaxBusLoad = 0.70;  // refuse a scene above this

struct BusTiming {
  double nominal_bitrate{1e6};  // arbitration phase [bit/s]
  double data_bitrate{5e6};     // FD data phase with bit-rate switch [bit/s]
};

struct FrameBits {
  int nominal{0};  // bits at the nominal rate
  int data{0};     // bits at the data rate (FD with BRS), 0 for classic frames
};

constexpr FrameBits classic_frame_bits(std::size_t n) {
  const int stuffable = 34 + 8 * static_cast<int>(n);
  return FrameBits{stuffable + (stuffable - 1) / 4 + 13, 0};
}

constexpr FrameBits fd_frame_bits(std::size_t n) {
  const int payload = 8 * static_cast<int>(n);
  const int dynamic_stuff = (21 + payload) / 4 - 4;
  const int crc = n <= 16 ? 17 : 21;
  const int fixed_stuff = n <= 16 ? 6 : 7;
  return FrameBits{17 + 4 + 12, 5 + payload + dynamic_stuff + 4 + crc + fixed_stuff + 1};
}

// Time on the bus of one frame [s].
constexpr double frame_time_s(FrameBits b, const BusTiming& t) {
  return b.nominal / t.nominal_bitrate + b.data / t.data_bitrate;
}

struct BusLoad {
  double load{0.0};             // fraction of the bus time used [-]
  double frames_per_s{0.0};     // both directions [1/s]
  double busy_s_per_tick{0.0};  // bus time of one tick's sensor and command sets [s]
  int frames_per_tick{0};
  bool acceptable() const { return load <= kMaxBusLoad; }
};

// Load of one sensor set and one command set per tick, at tick_rate_hz, on a device's bus.
constexpr BusLoad bus_load(const DeviceBus& bus, double tick_rate_hz, const BusTiming& timing) {
  BusLoad b;
  const std::span<const MessageSpec> messages = bus.messages();
  for (std::size_t i = 0; i < messages.size(); ++i) {
    b.busy_s_per_tick += frame_time_s(fd_frame_bits(messages[i].length), timing);
    ++b.frames_per_tick;
  }
  b.load = b.busy_s_per_tick * tick_rate_hz;
  b.frames_per_s = b.frames_per_tick * tick_rate_hz;
  return b;
}

static_assert(classic_frame_bits(8).nominal == 135, "worst-case classic 8-byte frame");
static_assert(fd_frame_bits(64).nominal == 33 && fd_frame_bits(64).data == 679, "worst-case FD 64-byte frame");

}  // namespace gyrostab::can
