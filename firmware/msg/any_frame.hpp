// The frames as a transport, a log or a run mode sees them, whatever the device: the fixed header and room for
// the most signals any device has. A device's typed frame (gyrostab_signals/<device>_frames.hpp) is a prefix of
// these bytes — the same header, then its own doubles — so to_any/from_any are one memcpy each, and the device's
// DeviceSignals (signal_spec.hpp) says how many of `signal` are in use and what each one is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>

#include "firmware/msg/signal_spec.hpp"

namespace gyrostab::msg {

struct AnySensorFrame {
  std::uint64_t tick{0};           // controller tick this frame belongs to [tick]
  std::int64_t time_ns{0};         // publish time on the plant's clock [ns]
  std::int64_t sample_time_ns{0};  // when the signals were sampled [ns]
  std::uint32_t sequence{0};       // publisher's frame counter: +1 per frame, wraps at 2^32 [-]
  std::uint32_t status{0};         // SensorStatusBit set (fault_bits.hpp) [bits]
  double signal[kMaxSensorSignals]{};
};

struct AnyActuatorFrame {
  std::uint64_t tick{0};         // controller tick at which this command was computed [tick]
  std::int64_t time_ns{0};       // the tick's time, tick · tick_ns [ns]
  std::uint64_t sensor_tick{0};  // tick of the sensor frame the command was computed from [tick]
  std::uint32_t sequence{0};     // controller's frame counter: +1 per frame, wraps at 2^32 [-]
  std::uint32_t status{0};       // FaultBit set (fault_bits.hpp) [bits]
  double signal[kMaxCommandSignals]{};
};

static_assert(std::is_trivially_copyable_v<AnySensorFrame> && std::is_standard_layout_v<AnySensorFrame>);
static_assert(std::is_trivially_copyable_v<AnyActuatorFrame> && std::is_standard_layout_v<AnyActuatorFrame>);
static_assert(offsetof(AnySensorFrame, signal) == kFrameHeaderBytes);
static_assert(offsetof(AnyActuatorFrame, signal) == kFrameHeaderBytes);

// The number of doubles a typed frame carries after its header.
template <class Frame>
inline constexpr std::size_t signal_count_v = (sizeof(Frame) - kFrameHeaderBytes) / sizeof(double);

template <class Frame>
concept TypedFrame = std::is_trivially_copyable_v<Frame> && std::is_standard_layout_v<Frame> &&
                     sizeof(Frame) >= kFrameHeaderBytes && (sizeof(Frame) - kFrameHeaderBytes) % 8 == 0;

// Typed ⇄ generic. The generic frame's values past the typed frame's are left as they are (zero in every
// frame a run builds, since each run carries one device's frames only).
template <TypedFrame Frame>
void to_any(const Frame& f, AnySensorFrame& out) {
  static_assert(sizeof(Frame) <= sizeof(AnySensorFrame));
  std::memcpy(static_cast<void*>(&out), &f, sizeof(Frame));
}
template <TypedFrame Frame>
void to_any(const Frame& f, AnyActuatorFrame& out) {
  static_assert(sizeof(Frame) <= sizeof(AnyActuatorFrame));
  std::memcpy(static_cast<void*>(&out), &f, sizeof(Frame));
}
template <TypedFrame Frame>
void from_any(const AnySensorFrame& in, Frame& f) {
  static_assert(sizeof(Frame) <= sizeof(AnySensorFrame));
  std::memcpy(static_cast<void*>(&f), &in, sizeof(Frame));
}
template <TypedFrame Frame>
void from_any(const AnyActuatorFrame& in, Frame& f) {
  static_assert(sizeof(Frame) <= sizeof(AnyActuatorFrame));
  std::memcpy(static_cast<void*>(&f), &in, sizeof(Frame));
}

// The generic frame of a typed one, by its direction (a sensor frame has a sample time, an actuator frame the
// tick of the sensor frame it answers).
template <TypedFrame Frame>
  requires requires(const Frame& f) { f.sample_time_ns; }
AnySensorFrame any_of(const Frame& f) {
  AnySensorFrame out{};
  to_any(f, out);
  return out;
}
template <TypedFrame Frame>
  requires requires(const Frame& f) { f.sensor_tick; }
AnyActuatorFrame any_of(const Frame& f) {
  AnyActuatorFrame out{};
  to_any(f, out);
  return out;
}

// Value i of a typed frame, in table order (the fault monitor, the safe command and the finite check walk
// them without naming a field). O(1).
template <TypedFrame Frame>
double signal_value(const Frame& f, std::size_t i) {
  double v;
  std::memcpy(&v, reinterpret_cast<const unsigned char*>(&f) + kFrameHeaderBytes + i * sizeof(double), sizeof v);
  return v;
}
template <TypedFrame Frame>
void set_signal_value(Frame& f, std::size_t i, double v) {
  std::memcpy(reinterpret_cast<unsigned char*>(&f) + kFrameHeaderBytes + i * sizeof(double), &v, sizeof v);
}

// The specs of a typed frame's values (found by argument-dependent lookup in the generated header).
template <TypedFrame Frame>
constexpr std::span<const SignalSpec> specs_of() {
  return signal_specs(static_cast<const Frame*>(nullptr));
}
template <TypedFrame Frame>
constexpr const DeviceSignals& device_of() {
  return device_signals(static_cast<const Frame*>(nullptr));
}

}  // namespace gyrostab::msg
