// The plant side's acceptance test of an ActuatorFrame, independent of the transport (LCM, CAN FD, the target
// link) and of the device: what a drive checks before it applies a command.
//   values   every command of the device finite and within its signal table's range [min, max] (the brake
//            in [0, 1], a torque within the drive's plausible range) and within the scene's magnitude limit
//            (ActuatorLimits: the law's torque limit, the steering's rate limit; 0 for a command the scene's
//            hardware does not have);
//   order    the frame is for the tick the plant expects; its sequence advances from the last accepted one
//            (serial-number arithmetic, wraps at 2^32); an exact repeat of the last accepted frame is
//            "repeated", an older tick or a non-advancing sequence "stale", a later tick "ahead".
// A frame that fails either is rejected whole and counted; the plant then treats the tick as having no
// command: the drive's watchdog gives zero torque (see drive_watchdog_command()).
// O(commands), no heap, no I/O.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/signal_spec.hpp"
#include "hil/link/link_counters.hpp"

namespace gyrostab::hil {

// Magnitude limits of the commands a plant's drives accept, per command value in the device's frame order, on
// top of the signal table's range. Default: none (the table's range only).
struct ActuatorLimits {
  // The limits as a typed actuator frame whose command fields hold each command's magnitude limit
  // (+infinity: none; 0: the scene's hardware has no such drive).
  template <msg::TypedFrame Frame>
  static ActuatorLimits of(const Frame& limits) {
    ActuatorLimits l;
    for (std::size_t i = 0; i < msg::signal_count_v<Frame>; ++i) l.magnitude[i] = msg::signal_value(limits, i);
    l.from_scene = true;
    return l;
  }
  // A typed actuator frame with every command unlimited, to set a scene's limits on (of()).
  template <msg::TypedFrame Frame>
  static Frame unlimited() {
    Frame f{};
    for (std::size_t i = 0; i < msg::signal_count_v<Frame>; ++i)
      msg::set_signal_value(f, i, std::numeric_limits<double>::infinity());
    return f;
  }

  double magnitude[msg::kMaxCommandSignals]{
      kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf};
  bool from_scene{false};  // false: the device gave no limits (its table's ranges only)

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
};
static_assert(msg::kMaxCommandSignals == 16, "ActuatorLimits' initializer has one +inf per command value");

enum class ActuatorVerdict { kOk, kNonFinite, kOutOfRange };

inline ActuatorVerdict check_actuator_values(const msg::AnyActuatorFrame& f, const msg::DeviceSignals& device,
                                             const ActuatorLimits& lim) {
  const std::size_t n = device.commands.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(f.signal[i])) return ActuatorVerdict::kNonFinite;
  for (std::size_t i = 0; i < n; ++i) {
    const msg::SignalSpec& s = device.commands[i];
    const double v = f.signal[i];
    if (v < s.min || v > s.max || std::fabs(v) > lim.magnitude[i]) return ActuatorVerdict::kOutOfRange;
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
inline msg::AnyActuatorFrame drive_watchdog_command(std::uint64_t tick) {
  msg::AnyActuatorFrame f{};
  f.tick = tick;
  return f;
}

}  // namespace gyrostab::hil
