// Fault monitor: the controller's watchdog on sensor frames (docs/architecture.md, bad input and safe
// states). Every tick it checks the frame that arrived (or that none did), counts each cause, bridges a short
// run of bad ticks by holding the last good frame, and then latches the safe state
// (firmware/fault/safe_state.hpp) with the reason in the status bits of every ActuatorFrame.
//
// Causes (FaultBit, msg/fault_bits.hpp), checked in this order each tick:
//   kSensorMissing        no frame this tick (check(nullptr, tick));
//   kSensorStale          the frame is not new: its sequence does not advance (serial-number arithmetic,
//                         wraps at 2^32), its tick does not advance, it is older than max_age_ticks, or it is
//                         stamped ahead of the controller's tick. A stale frame is rejected whole (no content
//                         checks, it does not move the sequence tracking);
//   kSensorNonFinite      a signal is NaN or ±Inf;
//   kSensorOutOfRange     a finite signal is outside its Range (config.ranges);
//   kSensorReportedFault  the frame's status has a bit in config.fault_sensor_status.
// A sequence that jumps forward (frames lost in transport) is not a fault: the lost frames are counted.
//
// State machine (one transition per check):
//   kAwaitingFirstFrame --good--> kNormal            output: safe command + kAwaitingFirstFrame until then
//   kNormal  --good--> kNormal;  --bad--> kHolding (or kSafe at once when hold_ticks == 0)
//   kHolding --good--> kNormal;  --bad--> kHolding while the run of bad ticks ≤ hold_ticks, else kSafe
//   kSafe    --acknowledge() then a good frame--> kNormal;  anything else stays kSafe
// So with the default hold_ticks = 1, a first bad tick k is held (control runs on the frame of the last good
// tick), and if tick k + 1 is bad too the command of tick k + 1 is the safe command. In general the safe
// state starts at the (hold_ticks + 1)-th consecutive bad tick.
//
// Recovery rule: latched, only when told. acknowledge() arms one attempt, taken at the next check: a good
// frame there returns to kNormal; a bad one refuses it (counted) and a new acknowledge() is needed. Why not
// "after N good frames": a stabilizer that re-engages by itself releases the precession brake and restarts
// torque on a spinning rotor without anyone deciding to — the "unexpected start-up" that machine safety
// (EN ISO 14118, STO in IEC 61800-5-2) forbids; an intermittent sensor would also make the brake chatter.
// Power-on is the exception: the first good frame arms the monitor, because starting the run is the
// operator's decision. acknowledge() also resynchronises the sequence tracking (a restarted sensor side
// starts again at sequence 0).
//
// Generic over the device's typed sensor frame (its values and their ranges walked in frame order). Resources:
// one frame copy (the last good frame) and counters; no heap, no OS. check() is O(values), apply() O(commands).
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/fault/safe_state.hpp"
#include "firmware/fault/sensor_ranges.hpp"
#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/fault_bits.hpp"

namespace gyrostab::firmware {

template <class SensorFrame>
struct FaultMonitorConfigOf {
  typename SensorFrame::Ranges ranges{};  // plausible range of every value (the table's by default)
  std::uint32_t hold_ticks{1};     // consecutive bad ticks bridged with the last good frame [tick]
  std::uint64_t max_age_ticks{0};  // how far frame.tick may lag the controller's tick (0: same tick) [tick]
  // SensorStatusBits that count as a fault (a saturated rate gyro is reported, not a fault) [bits].
  std::uint32_t fault_sensor_status{msg::bit(msg::SensorStatusBit::kEncoderError) |
                                    msg::bit(msg::SensorStatusBit::kDriveFault) |
                                    msg::bit(msg::SensorStatusBit::kRotorSpeedInvalid)};
};

enum class MonitorState : std::uint8_t { kAwaitingFirstFrame, kNormal, kHolding, kSafe };

struct FaultCounters {
  std::uint64_t good_frames{0};                              // ticks whose frame passed every check [-]
  std::uint64_t missing{0};                                  // ticks with kSensorMissing [-]
  std::uint64_t stale{0};                                    // ticks with kSensorStale [-]
  std::uint64_t non_finite{0};                               // ticks with kSensorNonFinite [-]
  std::uint64_t out_of_range{0};                             // ticks with kSensorOutOfRange [-]
  std::uint64_t sensor_reported{0};                          // ticks with kSensorReportedFault [-]
  std::uint64_t frames_lost{0};                              // frames skipped by forward sequence jumps [-]
  std::uint64_t held_ticks{0};                               // ticks that ran on the held last good frame [-]
  std::uint64_t safe_ticks{0};                               // ticks that ended in kSafe [-]
  std::uint64_t trips{0};                                    // entries into kSafe [-]
  std::uint64_t recoveries{0};                               // acknowledged returns from kSafe to kNormal [-]
  std::uint64_t acknowledgements_refused{0};                 // acknowledge() followed by a bad frame [-]
  std::uint8_t last_non_finite_signal{kNoSignal};    // value index of the latest signal found NaN/Inf
  std::uint8_t last_out_of_range_signal{kNoSignal};  // value index of the latest signal found out of range
};

template <class SensorFrame>
class FaultMonitorOf {
 public:
  using Config = FaultMonitorConfigOf<SensorFrame>;
  explicit FaultMonitorOf(const Config& config = {}) : config_(config) {}

  // Checks this tick's frame (`frame` == nullptr: none arrived) at controller tick `tick` and steps the state
  // machine. Returns the frame the control laws must use this tick — this tick's frame if good, the held last
  // good frame while holding — or nullptr when they must not run (awaiting the first frame, safe state).
  // The pointer stays valid until the next check().
  const SensorFrame* check(const SensorFrame* frame, std::uint64_t tick) {
    causes_ = classify(frame, tick);
    const bool good = causes_ == 0;
    if (good) {
      last_good_ = *frame;
      ++counters_.good_frames;
    }

    switch (state_) {
      case MonitorState::kAwaitingFirstFrame:
        if (good) state_ = MonitorState::kNormal;
        break;
      case MonitorState::kNormal:
      case MonitorState::kHolding:
        if (good) {
          state_ = MonitorState::kNormal;
          bad_run_ = 0;
          reason_ = 0;
        } else {
          ++bad_run_;
          reason_ |= causes_;
          if (bad_run_ > config_.hold_ticks) {
            state_ = MonitorState::kSafe;
            ++counters_.trips;
          } else {
            state_ = MonitorState::kHolding;
          }
        }
        break;
      case MonitorState::kSafe:
        if (acknowledge_pending_) {
          acknowledge_pending_ = false;
          if (good) {
            state_ = MonitorState::kNormal;
            bad_run_ = 0;
            reason_ = 0;
            ++counters_.recoveries;
          } else {
            ++counters_.acknowledgements_refused;
          }
        }
        break;
    }

    if (state_ == MonitorState::kHolding) ++counters_.held_ticks;
    if (state_ == MonitorState::kSafe) ++counters_.safe_ticks;
    const bool run_control = state_ == MonitorState::kNormal || state_ == MonitorState::kHolding;
    return run_control ? &last_good_ : nullptr;
  }

  // Adds the monitor's status bits to `command` and, awaiting the first frame or in the safe state, replaces
  // its commands with the safe command. Call on every ActuatorFrame after the control laws. O(1).
  template <msg::TypedFrame ActuatorFrame>
  void apply(ActuatorFrame& command) const {
    command.status |= status();
    if (state_ == MonitorState::kAwaitingFirstFrame || state_ == MonitorState::kSafe) {
      command_safe_state(command);
    }
  }

  // Asks to leave the safe state; taken at the next check() (see the recovery rule above). Ignored outside
  // the safe state.
  void acknowledge() {
    if (state_ != MonitorState::kSafe) return;
    acknowledge_pending_ = true;
    have_seen_ = false;
  }

  // The bits apply() adds: kHoldingLastGood or kSafeState with the causes of the current run of bad ticks
  // (in kSafe: latched, the causes of the run that tripped it); kSafeState | kAwaitingFirstFrame and this
  // tick's causes before the first good frame; 0 in kNormal.
  std::uint32_t status() const {
    switch (state_) {
      case MonitorState::kAwaitingFirstFrame:
        return msg::bit(msg::FaultBit::kSafeState) | msg::bit(msg::FaultBit::kAwaitingFirstFrame) | causes_;
      case MonitorState::kNormal:
        return 0;
      case MonitorState::kHolding:
        return msg::bit(msg::FaultBit::kHoldingLastGood) | reason_;
      case MonitorState::kSafe:
        return msg::bit(msg::FaultBit::kSafeState) | reason_;
    }
    return msg::bit(msg::FaultBit::kSafeState);
  }

  MonitorState state() const { return state_; }
  std::uint32_t causes() const { return causes_; }  // cause bits found by the latest check()
  const FaultCounters& counters() const { return counters_; }
  const SensorFrame& last_good() const { return last_good_; }
  const Config& config() const { return config_; }

 private:
  // The cause bits of this tick's frame; updates the per-cause counters and the sequence tracking.
  std::uint32_t classify(const SensorFrame* frame, std::uint64_t tick) {
    using msg::FaultBit;
    if (frame == nullptr) {
      ++counters_.missing;
      return msg::bit(FaultBit::kSensorMissing);
    }
    const bool ahead = frame->tick > tick;
    const bool too_old = !ahead && tick - frame->tick > config_.max_age_ticks;
    const bool not_advancing =
        have_seen_ &&
        (frame->tick <= seen_tick_ || static_cast<std::int32_t>(frame->sequence - seen_sequence_) <= 0);
    if (ahead || too_old || not_advancing) {
      ++counters_.stale;
      return msg::bit(FaultBit::kSensorStale);
    }
    if (have_seen_) counters_.frames_lost += frame->sequence - seen_sequence_ - 1u;
    have_seen_ = true;
    seen_tick_ = frame->tick;
    seen_sequence_ = frame->sequence;

    std::uint32_t causes = 0;
    for_each_signal(*frame, config_.ranges, [&](std::uint8_t id, double value, const Range& range) {
      if (!std::isfinite(value)) {
        causes |= msg::bit(FaultBit::kSensorNonFinite);
        counters_.last_non_finite_signal = id;
      } else if (!range.contains(value)) {
        causes |= msg::bit(FaultBit::kSensorOutOfRange);
        counters_.last_out_of_range_signal = id;
      }
    });
    if ((frame->status & config_.fault_sensor_status) != 0u)
      causes |= msg::bit(FaultBit::kSensorReportedFault);

    if (msg::has(causes, FaultBit::kSensorNonFinite)) ++counters_.non_finite;
    if (msg::has(causes, FaultBit::kSensorOutOfRange)) ++counters_.out_of_range;
    if (msg::has(causes, FaultBit::kSensorReportedFault)) ++counters_.sensor_reported;
    return causes;
  }

  Config config_;
  MonitorState state_{MonitorState::kAwaitingFirstFrame};
  SensorFrame last_good_{};
  FaultCounters counters_{};
  std::uint32_t causes_{0};   // this tick's causes
  std::uint32_t reason_{0};   // causes of the current run of bad ticks (latched in kSafe)
  std::uint32_t bad_run_{0};  // consecutive bad ticks [tick]
  bool acknowledge_pending_{false};
  bool have_seen_{false};  // seen_* hold the last frame that was not stale
  std::uint64_t seen_tick_{0};
  std::uint32_t seen_sequence_{0};
};

}  // namespace gyrostab::firmware
