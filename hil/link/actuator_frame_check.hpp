// The plant side's acceptance test of an ActuatorFrame, independent of the transport (LCM here; the CAN
// FD transport, hil/can/, reuses it): what a drive checks before it applies a command.
//   values   every torque, voltage, cluster rate command and the brake finite; |torque| ≤ torque limit and
//            |voltage| ≤ voltage limit per gimbal axis, |rate command| ≤ the cluster's rate limit per unit (the
//            scene's limits, ActuatorLimits); brake in [0, 1];
//   order    the frame is for the tick the plant expects; its sequence advances from the last accepted one
//            (serial-number arithmetic, wraps at 2^32); an exact repeat of the last accepted frame is
//            "repeated", an older tick or a non-advancing sequence "stale", a later tick "ahead".
// A frame that fails either is rejected whole and counted; the plant then treats the tick as having no
// command: the drive's watchdog gives zero torque (see drive_watchdog_command()).
// O(1), no heap, no I/O.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "firmware/msg/actuator_frame.hpp"
#include "hil/link/link_counters.hpp"

namespace gyrostab::hil {

// Magnitude limits of the commands a plant accepts, per gimbal axis. Default: no magnitude limit (finite
// only).
struct ActuatorLimits {
  // A torque-mode drive with one limit on both axes (the voltages are unused: no limit).
  static ActuatorLimits torque_limited(double limit_Nm) {
    ActuatorLimits l;
    l.torque_Nm[0] = l.torque_Nm[1] = limit_Nm;
    l.from_scene = true;
    return l;
  }

  double torque_Nm[msg::kGimbalAxes]{std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::infinity()};  // |torque| ≤ this [N m]
  double voltage_V[msg::kGimbalAxes]{std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::infinity()};  // |voltage| ≤ this [V]
  double cluster_rate_rad_s{std::numeric_limits<double>::infinity()};  // |cluster rate command| ≤ this [rad/s]
  bool from_scene{
      false};  // false: the device gave no limits (only finiteness and the brake range are checked)
};

enum class ActuatorVerdict { kOk, kNonFinite, kOutOfRange };

inline ActuatorVerdict check_actuator_values(const msg::ActuatorFrame& f, const ActuatorLimits& lim) {
  bool finite = std::isfinite(f.precession_brake);
  for (std::size_t a = 0; a < msg::kGimbalAxes; ++a) {
    finite = finite && std::isfinite(f.gimbal_torque_Nm[a]) && std::isfinite(f.motor_voltage_V[a]);
  }
  for (std::size_t u = 0; u < msg::kClusterUnits; ++u) finite = finite && std::isfinite(f.cluster_rate_command_rad_s[u]);
  if (!finite) return ActuatorVerdict::kNonFinite;
  if (f.precession_brake < 0.0 || f.precession_brake > 1.0) return ActuatorVerdict::kOutOfRange;
  for (std::size_t a = 0; a < msg::kGimbalAxes; ++a) {
    if (std::fabs(f.gimbal_torque_Nm[a]) > lim.torque_Nm[a]) return ActuatorVerdict::kOutOfRange;
    if (std::fabs(f.motor_voltage_V[a]) > lim.voltage_V[a]) return ActuatorVerdict::kOutOfRange;
  }
  for (std::size_t u = 0; u < msg::kClusterUnits; ++u) {
    if (std::fabs(f.cluster_rate_command_rad_s[u]) > lim.cluster_rate_rad_s) return ActuatorVerdict::kOutOfRange;
  }
  return ActuatorVerdict::kOk;
}

enum class OrderVerdict { kExpected, kRepeated, kStale, kAhead, kJump };

// Both ends send one frame per tick and count it in the sequence (the plant's sequence is the tick, the
// controller's advances once per step), so between two accepted frames the sequence advances by at most the
// ticks between them. A frame whose sequence jumps further is refused (kJump): accepted, it would make every
// genuine frame after it look stale and lock the genuine peer out for good.
inline constexpr std::uint32_t kSequenceSlack = 2;

// Tracks the last accepted (tick, sequence) of one stream of frames and classifies the next one against the
// tick the receiver expects. Shared by both directions (a SensorFrame and an ActuatorFrame carry the same
// tick/sequence header semantics).
class FrameOrder {
 public:
  OrderVerdict classify(std::uint64_t tick, std::uint32_t sequence, std::uint64_t expected_tick) const {
    if (have_last_ && tick == last_tick_ && sequence == last_sequence_) return OrderVerdict::kRepeated;
    if (tick < expected_tick) return OrderVerdict::kStale;
    if (!sequence_advances(sequence)) return OrderVerdict::kStale;
    if (have_last_ && tick >= last_tick_ &&
        static_cast<std::uint64_t>(sequence - last_sequence_) > (tick - last_tick_) + kSequenceSlack) {
      return OrderVerdict::kJump;
    }
    if (tick > expected_tick) return OrderVerdict::kAhead;
    return OrderVerdict::kExpected;
  }
  void accept(std::uint64_t tick, std::uint32_t sequence) {
    have_last_ = true;
    last_tick_ = tick;
    last_sequence_ = sequence;
  }
  bool have_last() const { return have_last_; }
  // The sequence moved on from the last accepted frame: a frame sent after it, not a copy or a replay.
  bool sequence_advances(std::uint32_t sequence) const {
    return !have_last_ || static_cast<std::int32_t>(sequence - last_sequence_) > 0;
  }
  std::uint64_t last_tick() const { return last_tick_; }

 private:
  bool have_last_{false};
  std::uint64_t last_tick_{0};
  std::uint32_t last_sequence_{0};
};

// Counts one rejection of an order verdict other than kExpected.
inline void count_order_rejection(OrderVerdict v, LinkCounters& c) {
  switch (v) {
    case OrderVerdict::kExpected:
      break;
    case OrderVerdict::kRepeated:
      ++c.rejected_repeated;
      break;
    case OrderVerdict::kStale:
      ++c.rejected_stale;
      break;
    case OrderVerdict::kAhead:
      ++c.rejected_ahead;
      break;
    case OrderVerdict::kJump:
      ++c.rejected_jump;
      break;
  }
}

// What the plant's drives do for a tick without an accepted command: de-energise (zero torque, zero voltage),
// as a real drive's command watchdog does. The precession brake is released (0): engaging it is the
// controller's decision (its safe state commands brake = 1); a drive has no business locking the gimbal, and
// a plant whose brake is spring-applied on power loss would model that in its own brake, not here.
inline msg::ActuatorFrame drive_watchdog_command(std::uint64_t tick) {
  msg::ActuatorFrame f{};
  f.tick = tick;
  return f;
}

}  // namespace gyrostab::hil
