// What a signal is, as a device's signal table declares it (tools/devices/<device>/<device>_signals.toml,
// docs/signals.md): the generated typed frames (gyrostab_signals/<device>_frames.hpp) carry one constexpr
// SignalSpec per value, and every transport, check and document that does not know the device walks these
// instead of naming a field. Target code: plain constexpr data, no heap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace gyrostab::msg {

// Every frame begins with the same 32-byte header (tick, two times, sequence, status), then its signals as
// IEEE-754 doubles in table order: byte offset of value i = kFrameHeaderBytes + 8 i, on every transport.
inline constexpr std::size_t kFrameHeaderBytes = 32;
// The most values a device's frame carries in each direction (the generic frames' capacity, any_frame.hpp).
inline constexpr std::size_t kMaxSensorSignals = 32;
inline constexpr std::size_t kMaxCommandSignals = 16;

// Closed interval [min, max] in the unit of the signal it guards. NaN is never contained.
struct Range {
  double min{0.0};
  double max{0.0};
  constexpr bool contains(double x) const { return min <= x && x <= max; }
};

// One value of a frame (an array signal has one spec per element, `element` counting from 0).
struct SignalSpec {
  std::string_view name;    // the table's name: C++ field, LCM field, the element's base name
  std::string_view symbol;  // the book's symbol
  std::string_view unit;    // SI unit ("-" for a ratio)
  double min;               // plausible range: the fault monitor's default (sensors), the drive's limit
  double max;               //   (commands) [unit]
  double safe;              // commands: the value in the safe state; sensors: 0
  std::string_view node;    // the CAN node that measures (sensors) or acts on (commands) it
  std::uint8_t element;     // index within its array (0 for a scalar)
  std::uint8_t count;       // elements of its array (1 for a scalar)
  std::string_view description;
};

// A device's interface: both directions' values in frame order, and their LCM types.
struct DeviceSignals {
  std::string_view device;
  std::span<const SignalSpec> sensors;
  std::span<const SignalSpec> commands;
  std::string_view lcm_sensor_type;    // "gyrostab_msg.<device>_sensor_t"
  std::string_view lcm_actuator_type;  // "gyrostab_msg.<device>_actuator_t"
  std::uint64_t lcm_sensor_fingerprint;
  std::uint64_t lcm_actuator_fingerprint;
};

}  // namespace gyrostab::msg
