// Plausibility ranges of the sensor values: each device's generated SensorRanges (gyrostab_signals/
// <device>_frames.hpp), one Range per value with its signal table's range as the default, narrowed by a scene.
// The fault monitor walks a frame's values and its ranges in frame order, so a signal added to a table is
// checked everywhere with nothing written here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/signal_spec.hpp"

namespace gyrostab::firmware {

using msg::Range;

inline constexpr double kPi = 3.14159265358979323846;

// The rotor-speed range of a device whose rotor spins at `nominal_rad_s`: ±1e4 rad/s, widened to twice the
// nominal speed for a faster rotor. A range narrower than the rotor's own speed would hold the controller in
// its safe state from the first frame (kSensorOutOfRange), which no scene could notice from its figures.
constexpr Range rotor_speed_range_for(double nominal_rad_s) {
  constexpr Range wide{-1e4, 1e4};
  const double twice = 2.0 * (nominal_rad_s < 0.0 ? -nominal_rad_s : nominal_rad_s);
  return twice > wide.max ? Range{-twice, twice} : wide;
}

// "No signal" (e.g. none found out of range yet) as a value index.
inline constexpr std::uint8_t kNoSignal = 0xFF;

// The range of value i of a typed ranges struct (one Range per value, in frame order). O(1).
template <class Ranges>
Range range_at(const Ranges& ranges, std::size_t i) {
  Range r;
  std::memcpy(&r, reinterpret_cast<const unsigned char*>(&ranges) + i * sizeof(Range), sizeof r);
  return r;
}

// Calls fn(value index, value, range) for every value of a typed sensor frame, in frame order.
// O(values).
template <msg::TypedFrame Frame, class Ranges, class Fn>
void for_each_signal(const Frame& frame, const Ranges& ranges, Fn&& fn) {
  static_assert(sizeof(Ranges) >= msg::signal_count_v<Frame> * sizeof(Range), "one Range per sensor value");
  for (std::size_t i = 0; i < msg::signal_count_v<Frame>; ++i) {
    fn(static_cast<std::uint8_t>(i), msg::signal_value(frame, i), range_at(ranges, i));
  }
}

}  // namespace gyrostab::firmware
