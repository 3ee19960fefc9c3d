// Controller runtime: what every device controller (firmware/app/*_controller.hpp) does around its control
// law — screen the sensor frame (fault monitor), run the tasks due at this tick (multi-rate scheduler with
// perf counters), publish one ActuatorFrame per tick with the header, the status bits and, when it must, the
// safe command. One API for every device, so a scene runner can drive any of them:
//
//   Controller c(config);                  // config.runtime below + the device's law parameters
//   if (!c.armed()) ... c.config_check()   // Config::check() verdict; a refused controller only outputs
//                                          // the safe command (with LawStatusBit::kConfigRefused)
//   c.step(tick, frame_or_nullptr, out);   // once per base tick
//   c.control_counters(), c.fault_counters(), ...   // for the run report
//
// Ticks and rates (docs/architecture.md, the loop). The base tick is the period at which step() is called, a
// SensorFrame is expected and an ActuatorFrame is published: T_b = tick_period_ns. Tasks, in this order
// within a tick:
//   control  every control_divisor ticks, phase 0: the control law, period T_c = control_divisor · T_b
//   drive    every drive_divisor ticks, phase 0 (only when the drive is enabled): the current loops,
//            period T_d = drive_divisor · T_b
// with control_divisor a multiple of drive_divisor, so every control tick is also a drive tick and the
// drive, added after the control task, converts the fresh torque in the same tick (no added latency).
// Examples: base 1 ms → divisors 1, 1 (law and drives at 1 kHz); base 100 µs → control_divisor 10 (law at
// 1 kHz), drive_divisor 1 (current loops at 10 kHz). Between control runs the law's command is held
// (zero-order hold); the fault monitor screens every base tick. A law's dt is T_c, a drive's T_d.
//
// One step(tick, frame, out):
//   1. screened = monitor.check(frame, tick) — this tick's frame if good, the held last good frame while
//      holding, nullptr awaiting the first frame or in the safe state (firmware/fault/fault_monitor.hpp);
//      with nullptr the law and drive states are reset and the held command becomes the safe values;
//   2. scheduler.run_tick(tick): the due tasks run on `screened` (they skip when it is nullptr);
//   3. out = the held command (torques, voltages, brake, law status bits), with
//      tick, time_ns = tick · T_b (the controller's clock in deterministic runs), sensor_tick = tick of the
//      frame the latest control run used, sequence = +1 per published frame (from 0, wraps at 2^32);
//      a refused configuration or a non-finite command ⇒ the safe command (+ kConfigRefused /
//      kNonFiniteCommand); finally monitor.apply(out) adds kHoldingLastGood / kSafeState + the reason bits
//      and, awaiting the first frame or in the safe state, the safe command (brake on, zero torque and
//      voltage, firmware/fault/safe_state.hpp).
// So a missing or NaN frame at tick k is held (command from the last good frame, kHoldingLastGood), and a
// second bad tick k + 1 gives the safe state with the reason bit (hold_ticks = 1, the default). Recovery
// only through acknowledge() and a good frame (the monitor's rule); until the law has run again the held
// command is the safe values (brake on), so a recovering controller never releases the brake on stale data.
//
// A device ("law adapter") D provides
//   using SensorFrame = ...; using ActuatorFrame = ...;   // its typed frames (gyrostab_signals/<device>_frames.hpp)
//   void control(const SensorFrame& in, ActuatorFrame& cmd)   // writes its commands and its law status bits
//   void reset()                                              // frame withheld: clear state
//   (with a drive) static constexpr DriveSignals kDriveSignals[kDriveChannels]   // which values each current
//                                                                               // loop reads and writes
// and the controller passes the mask of drive channels whose torque the drive task converts to a voltage.
// The safe values, the finite check and the fault monitor's ranges come from the device's signal table.
// Resources: the device, the monitor (one SensorFrame), a 2-task scheduler, two current loops; no heap, no
// exceptions, no I/O. step() is O(1). Not copyable or movable (the scheduler holds `this`).
// Tests: tests/unit/controllers_test.cpp.
// Docs: docs/models/README.md#firmware
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/torque_current_loop.hpp"
#include "firmware/fault/fault_monitor.hpp"
#include "firmware/fault/safe_state.hpp"
#include "firmware/msg/any_frame.hpp"
#include "firmware/scheduler/clock.hpp"
#include "firmware/scheduler/scheduler.hpp"

namespace gyrostab::firmware {

template <class SensorFrame>
struct RuntimeConfigOf {
  std::int64_t tick_period_ns{1'000'000};  // T_b, base tick [ns]
  std::uint32_t control_divisor{1};        // control law every this many base ticks [-]
  std::uint32_t drive_divisor{1};          // drive loops every this many base ticks; divides control_divisor
  std::int64_t control_budget_ns{0};  // compute budget of one control run (overrun count); ≤ 0: none [ns]
  std::int64_t drive_budget_ns{0};    // same for one drive run [ns]
  FaultMonitorConfigOf<SensorFrame> monitor{};  // ranges, hold_ticks, max_age_ticks, sensor status faults

  constexpr double tick_period_s() const { return static_cast<double>(tick_period_ns) * 1e-9; }
  constexpr double control_period_s() const { return tick_period_s() * static_cast<double>(control_divisor); }
  constexpr double drive_period_s() const { return tick_period_s() * static_cast<double>(drive_divisor); }
};

// A device's gimbal drives: up to two channels (the book's axes 1 and 2 of a single-rotor device).
inline constexpr std::size_t kDriveChannels = 2;

// Current loops for voltage-driven gimbal motors; disabled: torque-mode drives, the voltages stay 0.
struct DriveConfig {
  bool enabled{false};
  TorqueCurrentLoopParams axis[kDriveChannels]{};  // per drive channel (only the device's channels are used)
};

// The values one drive channel's current loop works on (value indices in the device's typed frames):
// the law's torque command in, the voltage command out, the winding current and the gimbal rate measured.
struct DriveSignals {
  std::size_t torque;   // command value [N m]
  std::size_t voltage;  // command value [V]
  std::size_t current;  // sensor value [A]
  std::size_t rate;     // sensor value [rad/s]
};
// The typed frames of a law adapter (its own, generated from its signal table).
template <class Device>
struct DeviceFrames {
  using Sensor = typename Device::SensorFrame;
  using Actuator = typename Device::ActuatorFrame;
};

inline constexpr std::uint32_t axis_mask(std::size_t axis) {
  return 1u << axis;
}

// The runtime's part of every Config::check(): tick period and divisors, then the current loops of the axes
// in `drive_axes` if the drive is enabled. O(1).
template <class SensorFrame>
ConfigCheck check_runtime(const RuntimeConfigOf<SensorFrame>& rc, const DriveConfig& dc, std::uint32_t drive_axes) {
  if (!(rc.tick_period_ns > 0)) {
    return ConfigCheck::refused("runtime: tick_period_ns must be > 0",
                                static_cast<double>(rc.tick_period_ns));
  }
  if (rc.control_divisor == 0 || rc.drive_divisor == 0) {
    return ConfigCheck::refused("runtime: control_divisor and drive_divisor must be >= 1");
  }
  if (rc.control_divisor % rc.drive_divisor != 0) {
    return ConfigCheck::refused(
        "runtime: control_divisor must be a multiple of drive_divisor (every control tick is a drive tick)",
        static_cast<double>(rc.drive_divisor), 1.0, static_cast<double>(rc.control_divisor));
  }
  if (dc.enabled) {
    for (std::size_t a = 0; a < kDriveChannels; ++a) {
      if ((drive_axes & axis_mask(a)) == 0u) continue;
      const ConfigCheck d = check_torque_current_loop(dc.axis[a], rc.drive_period_s());
      if (!d.ok) return d;
    }
  }
  return ConfigCheck::accepted();
}

template <class Device, MonotonicClock Clock = NullClock>
class ControllerRuntime {
 public:
  using SchedulerType = Scheduler<2, Clock>;
  using SensorFrame = typename DeviceFrames<Device>::Sensor;
  using ActuatorFrame = typename DeviceFrames<Device>::Actuator;

  ControllerRuntime(const RuntimeConfigOf<SensorFrame>& rc, const DriveConfig& dc, std::uint32_t drive_axes,
                    const Device& device, const ConfigCheck& check, Clock clock = Clock{})
      : tick_period_ns_(rc.tick_period_ns),
        device_(device),
        check_(check),
        monitor_(rc.monitor),
        scheduler_(clock, 0),
        drive_axes_(dc.enabled && kHasDrive ? drive_axes : 0u) {
    set_held_to_safe_values();
    if (!check_.ok) return;  // refused: no task ever runs a law (the monitor still screens, for counters)
    for (std::size_t a = 0; a < kDriveChannels; ++a) {
      if ((drive_axes_ & axis_mask(a)) != 0u) drives_[a] = TorqueCurrentLoop(dc.axis[a], rc.drive_period_s());
    }
    const AddResult c = scheduler_.template add_member<&ControllerRuntime::control_task>(
        "control", rc.control_divisor, 0, rc.control_budget_ns, *this);
    control_id_ = c.id;
    if (drive_axes_ != 0u) {
      const AddResult d = scheduler_.template add_member<&ControllerRuntime::drive_task>(
          "drive", rc.drive_divisor, 0, rc.drive_budget_ns, *this);
      drive_id_ = d.id;
      has_drive_task_ = d.ok();
    }
  }
  ControllerRuntime(const ControllerRuntime&) = delete;
  ControllerRuntime& operator=(const ControllerRuntime&) = delete;

  // One base tick (see the header). `frame` == nullptr: no frame arrived this tick. O(1).
  void step(std::uint64_t tick, const SensorFrame* frame, ActuatorFrame& out) {
    screened_ = monitor_.check(frame, tick);
    if (screened_ == nullptr && !reset_done_) {
      device_.reset();
      for (TorqueCurrentLoop& d : drives_) d.reset();
      set_held_to_safe_values();
      reset_done_ = true;
    }
    if (screened_ != nullptr) reset_done_ = false;
    scheduler_.run_tick(tick);

    out = held_;
    out.status = held_.status | drive_status_;
    out.tick = tick;
    out.time_ns = static_cast<std::int64_t>(tick) * tick_period_ns_;
    out.sensor_tick = sensor_tick_;
    out.sequence = sequence_++;
    if (!check_.ok) {
      command_safe_state(out);
      out.status |= bit(LawStatusBit::kConfigRefused);
    } else if (!finite_command(out)) {
      command_safe_state(out);
      out.status |= bit(LawStatusBit::kNonFiniteCommand);
    }
    monitor_.apply(out);
  }

  // Asks the fault monitor to leave the safe state at the next good frame (the monitor's recovery rule).
  void acknowledge() { monitor_.acknowledge(); }

  bool armed() const { return check_.ok; }
  const ConfigCheck& config_check() const { return check_; }
  std::int64_t tick_period_ns() const { return tick_period_ns_; }

  // Counters for the run report.
  const PerfCounter& control_counters() const { return scheduler_.counters(control_id_); }
  const PerfCounter& drive_counters() const {
    return has_drive_task_ ? scheduler_.counters(drive_id_) : kNoCounter;
  }
  const PerfCounter& tick_counters() const { return scheduler_.tick_counters(); }
  std::uint64_t ticks_run() const { return scheduler_.ticks_run(); }
  std::uint64_t ticks_skipped() const { return scheduler_.ticks_skipped(); }
  std::uint64_t ticks_repeated() const { return scheduler_.ticks_repeated(); }
  bool has_drive_task() const { return has_drive_task_; }
  const FaultCounters& fault_counters() const { return monitor_.counters(); }
  MonitorState monitor_state() const { return monitor_.state(); }
  std::uint32_t monitor_status() const { return monitor_.status(); }
  std::uint32_t next_sequence() const { return sequence_; }

  const SchedulerType& scheduler() const { return scheduler_; }
  const FaultMonitorOf<SensorFrame>& monitor() const { return monitor_; }
  const Device& device() const { return device_; }

 protected:
  Device& mutable_device() { return device_; }

 private:
  static inline const PerfCounter kNoCounter{};
  // A device without kDriveSignals has no current loops: its drive task never runs, whatever the config says.
  static constexpr bool kHasDrive = requires { Device::kDriveSignals; };

  void control_task(std::uint64_t /*tick*/) {
    if (screened_ == nullptr) return;
    held_.status = 0;
    device_.control(*screened_, held_);
    held_.status &= ~(msg::kFaultCauseMask | 0xFFFFu);  // a law writes only bits 16-31
    sensor_tick_ = screened_->tick;
  }

  void drive_task(std::uint64_t /*tick*/) {
    if constexpr (kHasDrive) {
      if (screened_ == nullptr) return;
      drive_status_ = 0;
      for (std::size_t a = 0; a < kDriveChannels; ++a) {
        if ((drive_axes_ & axis_mask(a)) == 0u) continue;
        const DriveSignals& d = Device::kDriveSignals[a];
        const TorqueCurrentOutput o = drives_[a].step(msg::signal_value(held_, d.torque),
                                                      msg::signal_value(*screened_, d.current),
                                                      msg::signal_value(*screened_, d.rate));
        msg::set_signal_value(held_, d.voltage, o.voltage_V);
        if (o.saturated) drive_status_ |= bit(LawStatusBit::kDriveVoltageSaturated);
      }
    }
  }

  void set_held_to_safe_values() {
    set_safe_values(held_);
    held_.status = 0;
    drive_status_ = 0;
  }

  static bool finite_command(const ActuatorFrame& c) {
    bool ok = true;
    for (std::size_t i = 0; i < msg::signal_count_v<ActuatorFrame>; ++i) ok = ok && std::isfinite(msg::signal_value(c, i));
    return ok;
  }

  std::int64_t tick_period_ns_;
  Device device_;
  ConfigCheck check_;
  FaultMonitorOf<SensorFrame> monitor_;
  SchedulerType scheduler_;
  TorqueCurrentLoop drives_[kDriveChannels]{};
  std::uint32_t drive_axes_{0};
  std::size_t control_id_{0};
  std::size_t drive_id_{0};
  bool has_drive_task_{false};
  const SensorFrame* screened_{nullptr};
  bool reset_done_{true};
  ActuatorFrame held_{};           // the command between control runs (header fields unused)
  std::uint32_t drive_status_{0};  // drive bits of the latest drive run
  std::uint64_t sensor_tick_{0};
  std::uint32_t sequence_{0};
};

}  // namespace gyrostab::firmware
