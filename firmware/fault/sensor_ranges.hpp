// Plausibility ranges for every SensorFrame signal, and one place that walks the signals: the fault monitor
// checks each signal for NaN/Inf and against its range with for_each_signal, so a signal added to the
// contract is added here once and is checked everywhere.
//
// The defaults are wide (what no shipped device can physically reach); a scene narrows them to its device.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

// Closed interval [min, max] in the unit of the signal it guards. NaN is never contained.
struct Range {
  double min{0.0};
  double max{0.0};
  constexpr bool contains(double x) const { return min <= x && x <= max; }
};

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr Range kAnyInt32{-2147483648.0, 2147483647.0};

struct SensorRanges {
  Range carrier_angle_rad[msg::kCarrierAxes]{{-kPi, kPi}, {-kPi, kPi}, {-kPi, kPi}};         // [rad]
  Range carrier_rate_rad_s[msg::kCarrierAxes]{{-10.0, 10.0}, {-10.0, 10.0}, {-10.0, 10.0}};  // [rad/s]
  Range gimbal_angle_rad[msg::kGimbalAxes]{{-kPi, kPi}, {-kPi, kPi}};                        // [rad]
  Range gimbal_rate_rad_s[msg::kGimbalAxes]{{-1e3, 1e3}, {-1e3, 1e3}};                       // [rad/s]
  Range motor_current_A[msg::kGimbalAxes]{{-1e3, 1e3}, {-1e3, 1e3}};                         // [A]
  Range rotor_speed_rad_s{-1e4, 1e4};                                                        // [rad/s]
  Range encoder_count[msg::kGimbalAxes]{kAnyInt32, kAnyInt32};                               // [counts]
  Range cluster_gimbal_angle_rad[msg::kClusterUnits]{{-kPi, kPi}, {-kPi, kPi}, {-kPi, kPi}, {-kPi, kPi}};  // [rad]
  Range cluster_gimbal_rate_rad_s[msg::kClusterUnits]{{-1e3, 1e3}, {-1e3, 1e3}, {-1e3, 1e3}, {-1e3, 1e3}};  // [rad/s]
};

// The rotor-speed range of a device whose rotor spins at `nominal_rad_s`: the default, widened to twice the
// nominal speed for a faster rotor. A range narrower than the rotor's own speed would hold the controller in
// its safe state from the first frame (kSensorOutOfRange), which no scene could notice from its figures.
constexpr Range rotor_speed_range_for(double nominal_rad_s) {
  const Range wide = SensorRanges{}.rotor_speed_rad_s;
  const double twice = 2.0 * (nominal_rad_s < 0.0 ? -nominal_rad_s : nominal_rad_s);
  return twice > wide.max ? Range{-twice, twice} : wide;
}

// Every checked signal of a SensorFrame, in contract order (for counters and diagnostics).
enum class SensorSignal : std::uint8_t {
  kCarrierAngleRoll,
  kCarrierAnglePitch,
  kCarrierAngleYaw,
  kCarrierRateRoll,
  kCarrierRatePitch,
  kCarrierRateYaw,
  kGimbalAngle1,
  kGimbalAngle2,
  kGimbalRate1,
  kGimbalRate2,
  kMotorCurrent1,
  kMotorCurrent2,
  kRotorSpeed,
  kEncoderCount1,
  kEncoderCount2,
  kClusterAngle1,
  kClusterAngle2,
  kClusterAngle3,
  kClusterAngle4,
  kClusterRate1,
  kClusterRate2,
  kClusterRate3,
  kClusterRate4,
  kNone,  // "no signal": e.g. no out-of-range signal seen yet
};
inline constexpr std::size_t kSensorSignalCount = static_cast<std::size_t>(SensorSignal::kNone);

// Calls fn(SensorSignal, double value, const Range&) for every signal of `frame`, in contract order.
// O(kSensorSignalCount).
template <class Fn>
constexpr void for_each_signal(const msg::SensorFrame& frame, const SensorRanges& ranges, Fn&& fn) {
  auto id = [](SensorSignal first, std::size_t i) {
    return static_cast<SensorSignal>(static_cast<std::size_t>(first) + i);
  };
  for (std::size_t i = 0; i < msg::kCarrierAxes; ++i) {
    fn(id(SensorSignal::kCarrierAngleRoll, i), frame.carrier_angle_rad[i], ranges.carrier_angle_rad[i]);
  }
  for (std::size_t i = 0; i < msg::kCarrierAxes; ++i) {
    fn(id(SensorSignal::kCarrierRateRoll, i), frame.carrier_rate_rad_s[i], ranges.carrier_rate_rad_s[i]);
  }
  for (std::size_t i = 0; i < msg::kGimbalAxes; ++i) {
    fn(id(SensorSignal::kGimbalAngle1, i), frame.gimbal_angle_rad[i], ranges.gimbal_angle_rad[i]);
  }
  for (std::size_t i = 0; i < msg::kGimbalAxes; ++i) {
    fn(id(SensorSignal::kGimbalRate1, i), frame.gimbal_rate_rad_s[i], ranges.gimbal_rate_rad_s[i]);
  }
  for (std::size_t i = 0; i < msg::kGimbalAxes; ++i) {
    fn(id(SensorSignal::kMotorCurrent1, i), frame.motor_current_A[i], ranges.motor_current_A[i]);
  }
  fn(SensorSignal::kRotorSpeed, frame.rotor_speed_rad_s, ranges.rotor_speed_rad_s);
  for (std::size_t i = 0; i < msg::kGimbalAxes; ++i) {
    fn(id(SensorSignal::kEncoderCount1, i), static_cast<double>(frame.encoder_count[i]),
       ranges.encoder_count[i]);
  }
  for (std::size_t i = 0; i < msg::kClusterUnits; ++i) {
    fn(id(SensorSignal::kClusterAngle1, i), frame.cluster_gimbal_angle_rad[i], ranges.cluster_gimbal_angle_rad[i]);
  }
  for (std::size_t i = 0; i < msg::kClusterUnits; ++i) {
    fn(id(SensorSignal::kClusterRate1, i), frame.cluster_gimbal_rate_rad_s[i], ranges.cluster_gimbal_rate_rad_s[i]);
  }
}

}  // namespace gyrostab::firmware
