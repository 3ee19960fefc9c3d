// The CAN maps and buses the unit tests walk (tests/unit/can_*_test.cpp): every map of the build
// (gyrostab_signals/all_can_maps.hpp: each signal table's) and the tests' own devices, tables with every shape
// of the layout (tests/signals/can_fixture_signals.toml) and every shipped device's signal shapes at once
// (tests/signals/union_fixture_signals.toml); each carried whole. And frames of random content that a bus carries
// exactly: doubles of every kind (NaN payloads, -0.0, subnormals, infinities) and, where a value rides as an
// integer, integers of its type up to its extremes.
#pragma once

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "firmware/msg/any_frame.hpp"
#include "gyrostab_signals/all_can_maps.hpp"
#include "gyrostab_signals/all_devices.hpp"
#include "gyrostab_signals/can_fixture_can.hpp"
#include "gyrostab_signals/union_fixture_can.hpp"
#include "hil/can/frame_map.hpp"
#include "sim/random/seeded_rng.hpp"

namespace gyrostab::can::testing {

inline std::vector<const CanMap*> test_can_maps() {
  std::vector<const CanMap*> maps(std::begin(kAllCanMaps), std::end(kAllCanMaps));
  maps.push_back(&can_fixture::kCanMap);
  maps.push_back(&union_fixture::kCanMap);
  return maps;
}

struct TestBus {
  DeviceBus bus;
  std::string label;
};

// Every map, whole.
inline std::vector<TestBus> test_buses() {
  std::vector<TestBus> out;
  for (const CanMap* m : test_can_maps()) out.push_back({whole_bus(*m), std::string(m->device)});
  return out;
}

// Where value i of a direction's frame rides (nullptr: no frame of the map carries it).
struct ValueOnBus {
  const MessageSpec* message{nullptr};
  const SignalSpec* signal{nullptr};
};

inline std::vector<ValueOnBus> values_on(const DeviceBus& bus, Direction d) {
  const std::size_t n = (bus.frame_bytes(d) - msg::kFrameHeaderBytes) / sizeof(double);
  std::vector<ValueOnBus> out(n);
  for (std::size_t i = 0; i < bus.messages().size(); ++i) {
    const MessageSpec& m = bus.messages()[i];
    if (m.direction != d) continue;
    for (const SignalSpec& s : m.signals) {
      if (s.field_offset < static_cast<int>(msg::kFrameHeaderBytes)) continue;
      const auto v = static_cast<std::size_t>(s.field_offset - static_cast<int>(msg::kFrameHeaderBytes)) / 8u;
      if (v < n) out[v] = {&m, &s};
    }
  }
  return out;
}

// A double of any kind, as a frame may hold one.
inline double any_double(random::SeededRng& rng) {
  switch (rng.next() % 10) {
    case 0: return -0.0;
    case 1: return std::numeric_limits<double>::denorm_min() * static_cast<double>(rng.next() % 1000);
    case 2: return std::bit_cast<double>(0x7FF8'0000'0000'0000ull | (rng.next() & 0xFFFF'FFFFull));  // NaN payload
    case 3: return (rng.next() & 1) != 0 ? std::numeric_limits<double>::infinity() : -1e300;
    default: return (rng.uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng.next() % 40) - 20);
  }
}

// An integer of an integer signal's type, its extremes often.
inline double any_integer(const SignalSpec& s, random::SeededRng& rng) {
  const int bits = s.bit_length;
  const double lo = s.kind == SignalKind::kSigned ? -std::ldexp(1.0, bits - 1) : 0.0;
  const double hi = s.kind == SignalKind::kSigned ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
  switch (rng.next() % 5) {
    case 0: return lo;
    case 1: return hi;
    default: return std::floor(lo + (hi - lo + 1.0) * rng.uniform());
  }
}

template <class Frame>
void fill_values(const DeviceBus& bus, Direction d, Frame& f, random::SeededRng& rng) {
  const std::vector<ValueOnBus> values = values_on(bus, d);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const ValueOnBus& v = values[i];
    f.signal[i] = v.signal == nullptr ? 0.0 : v.signal->integer ? any_integer(*v.signal, rng) : any_double(rng);
  }
}

inline msg::AnySensorFrame random_sensor(const DeviceBus& bus, std::uint64_t tick, random::SeededRng& rng) {
  msg::AnySensorFrame f{};
  f.tick = tick;
  f.time_ns = static_cast<std::int64_t>(rng.next());
  f.sample_time_ns = static_cast<std::int64_t>(rng.next());
  f.sequence = static_cast<std::uint32_t>(rng.next());
  f.status = static_cast<std::uint32_t>(rng.next());
  fill_values(bus, Direction::kSensor, f, rng);
  return f;
}

inline msg::AnyActuatorFrame random_actuator(const DeviceBus& bus, std::uint64_t tick, random::SeededRng& rng) {
  msg::AnyActuatorFrame f{};
  f.tick = tick;
  f.time_ns = static_cast<std::int64_t>(rng.next());
  f.sensor_tick = rng.next();
  f.sequence = static_cast<std::uint32_t>(rng.next());
  f.status = static_cast<std::uint32_t>(rng.next());
  fill_values(bus, Direction::kActuator, f, rng);
  return f;
}

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// The message of a map with this name.
inline const MessageSpec* message_named(const CanMap& map, std::string_view name) {
  for (const MessageSpec& m : map.messages)
    if (m.name == name) return &m;
  return nullptr;
}

}  // namespace gyrostab::can::testing
