// A device's CAN FD bus as data: which frames carry its interface (the generic frames msg::AnySensorFrame /
// AnyActuatorFrame with the device's msg::DeviceSignals), with identifier, length, sender, and every signal's
// position, type, scaling, unit and range. The maps are generated from the signal tables
// (tools/signals/can_layout.py decides the layout, generate.py writes gyrostab_signals/<device>_can.hpp, and
// gyrostab_signals/all_can_maps.hpp lists them); the codec (frame_codec.hpp), the DBC file (dbc_writer.hpp),
// the bus-load check (bus_load.hpp) and the link seal walk a map without knowing the device.
// tests/unit/can_frame_map_test.cpp checks that every map covers every byte of its device's frames once.
//
// Physical layer: CAN FD, 11-bit identifiers, bit-rate switch (1 Mbit/s arbitration, 5 Mbit/s data by
// default). Why FD and raw IEEE-754 doubles (docs/can.md has the arithmetic): lockstep runs over CAN must be
// bit-identical to in-process runs, so the controller must see exactly the doubles the plant computed. A value
// therefore travels as its double (factor 1, offset 0), or — the table's `can = "int32"` for a value that is
// always an integer, such as an encoder count — as that integer, which is as exact; the encoder refuses a
// value that is not one. The range is the table's plausible range, counted by the decoder; the decision about
// an implausible value stays with the firmware's fault monitor, exactly as in process.
//
// Every frame begins with the same 4-byte envelope (E2E-style protection, as AUTOSAR E2E profile 1 lays out):
//   byte 0      CRC-8 SAE J1850 (crc8.hpp) over the identifier (2 bytes, low byte first) and bytes 1..len-1
//   byte 1      bits 0-3: alive counter, +1 (mod 16) per frame sent on this identifier; bits 4-7: zero
//   bytes 2-3   tick tag: the low 16 bits of the tick the frame belongs to (the header frames also carry the
//               full 64-bit tick), so the receiver assembles a tick's frames and never mixes ticks
// Unused bytes up to the FD length are zero (covered by the CRC).
//
// The two header frames (SENSOR_HUB, CONTROLLER_CMD; 64 bytes) carry the frame header's fields at bytes 4-35,
// their node's values at 36-43, and end with the link envelope of the set, the one every plant ⇄ controller
// link carries (hil/link/link_guard.hpp, docs/transport.md):
//   bytes 44-47 sender id, 48-51 session id (both 32-bit: the ids are drawn as 32-bit values),
//   bytes 52-55 the low 32 bits of the sender's freshness counter (SecOC's truncated freshness value),
//   bytes 56-63 the MAC over the whole set (link_seal.hpp says which bytes); without a key an unkeyed
//               SipHash over the same bytes, which binds the body frames to their header.
// Plain constexpr data, no heap: the codec is firmware-grade.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

#include "firmware/msg/signal_spec.hpp"

namespace gyrostab::can {

// What a signal's raw bits are (all little-endian, "Intel" byte order in DBC terms).
enum class SignalKind : std::uint8_t { kUnsigned, kSigned, kDouble };

// Which generic frame a message carries: sensor messages go from the plant's nodes to the controller,
// actuator messages from the controller to the drive nodes.
enum class Direction : std::uint8_t { kSensor, kActuator };

struct SignalSpec {
  std::string_view name;      // DBC signal name
  std::uint16_t start_bit;    // position of the least significant bit in the payload (bit 0 = byte 0 bit 0)
  std::uint8_t bit_length;    // 64 for doubles
  SignalKind kind;
  int field_offset;           // byte offset of the field it carries in the generic frame; kEnvelope: none
  bool integer;               // a double field carried as an integer of bit_length bits (the table's can = ...)
  double factor;              // physical = raw · factor + offset
  double offset;
  double min;                 // plausible physical range [unit]
  double max;
  std::string_view unit;
  std::string_view comment;
};

struct MessageSpec {
  std::uint32_t id;           // 11-bit identifier; lower = higher priority on the bus
  std::string_view name;
  std::string_view sender;    // node name (DBC BU_)
  std::string_view node;      // whose frame: the node that measures (sensors) or acts on (commands) its values
  Direction direction;
  std::uint8_t length;        // FD data length [bytes]
  bool header;                // carries the frame header (full tick) and the link envelope: sent last
  std::span<const SignalSpec> signals;
  std::string_view comment;
};

// One device's map (gyrostab_signals/<device>_can.hpp): each direction's messages in the order they are sent,
// commands first, each direction's header last.
struct CanMap {
  std::string_view device;
  const msg::DeviceSignals* signals;  // the frames it carries
  std::span<const MessageSpec> messages;
  std::uint64_t fingerprint;          // of the layout (can_layout.py): a candump log records it
};

// Envelope (every message).
inline constexpr int kEnvelope = -1;
inline constexpr std::size_t kCrcByte = 0;
inline constexpr std::size_t kAliveByte = 1;
inline constexpr std::size_t kTickTagByte = 2;
inline constexpr std::size_t kEnvelopeBytes = 4;
inline constexpr std::uint8_t kAliveMask = 0x0F;

// Link envelope (header frames only).
inline constexpr std::size_t kLinkSenderByte = 44;
inline constexpr std::size_t kLinkSessionByte = 48;
inline constexpr std::size_t kLinkFreshnessByte = 52;
inline constexpr std::size_t kLinkMacByte = 56;
inline constexpr std::size_t kLinkFreshnessBytes = 4;
inline constexpr std::uint8_t kHeaderLength = 64;

// Capacities (can_layout.py refuses a table that needs more): the frames of one direction, of one map.
inline constexpr std::size_t kMaxMessagesPerDirection = 12;
inline constexpr std::size_t kMaxMessages = 2 * kMaxMessagesPerDirection;

// The bytes of the generic frame a signal carries: a value is a double even when it travels as an integer.
constexpr std::size_t field_bytes(const SignalSpec& s) {
  return s.integer ? sizeof(double) : s.bit_length / 8u;
}

// The messages one device's bus carries: every message of its map (generated from its signal table).
struct DeviceBus {
  const CanMap* map{nullptr};  // nullptr: no bus (no messages)

  constexpr std::span<const MessageSpec> messages() const {
    return map != nullptr ? map->messages : std::span<const MessageSpec>{};
  }
  // Index of the message with this identifier in the map, or -1. O(messages).
  constexpr int index_of(std::uint32_t id) const {
    const std::span<const MessageSpec> m = messages();
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m[i].id == id) return static_cast<int>(i);
    return -1;
  }
  // Bit i set: message i is part of a tick's set in this direction.
  constexpr std::uint32_t mask(Direction d) const {
    const std::span<const MessageSpec> m = messages();
    std::uint32_t out = 0;
    for (std::size_t i = 0; i < m.size(); ++i)
      if (m[i].direction == d) out |= 1u << i;
    return out;
  }
  constexpr std::size_t frames(Direction d) const {
    const std::span<const MessageSpec> m = messages();
    std::size_t n = 0;
    for (std::size_t i = 0; i < m.size(); ++i) n += m[i].direction == d;
    return n;
  }
  // The generic frame's bytes in use: header and the device's values.
  constexpr std::size_t frame_bytes(Direction d) const {
    if (map == nullptr || map->signals == nullptr) return msg::kFrameHeaderBytes;
    return msg::kFrameHeaderBytes +
           sizeof(double) * (d == Direction::kSensor ? map->signals->sensors.size() : map->signals->commands.size());
  }
};

// The bus of a device: its map, every message of it.
constexpr DeviceBus whole_bus(const CanMap& map) { return DeviceBus{&map}; }

static_assert(kMaxMessages <= 32, "message masks are 32-bit");
static_assert(std::numeric_limits<double>::is_iec559, "the bus carries IEEE-754 doubles");

}  // namespace gyrostab::can
