// The in-process closed loop (DESIGN §2), one tick:
//   1. the plant samples its sensors: SensorFrame{tick k};
//   2. the controller (firmware) steps on it and returns ActuatorFrame{tick k};
//   3. the command computed from the frame of tick k is applied at tick k + latency (zero-order hold;
//      until then the device's initial command), and the plant integrates [k, k + 1).
// Allocation-free: the latency pipe is a fixed array, the recorder's table is sized before the loop.
// A runtime guard stops at the first non-finite plant state and says at which tick and, for a device that
// names its state (state_guard.hpp), which component with its last finite value.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <unistd.h>

#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"
#include "tools/run/recorder.hpp"
#include "tools/run/state_guard.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

// A fresh SensorFrame for tick k: header from the integer tick (publish and sample time on the plant's clock,
// sequence = tick), every signal zero until the device fills it.
inline void begin_sensor_frame(msg::SensorFrame& f, std::int64_t tick, std::int64_t tick_ns) {
  f = msg::SensorFrame{};
  f.tick = static_cast<std::uint64_t>(tick);
  f.time_ns = tick * tick_ns;
  f.sample_time_ns = f.time_ns;
  f.sequence = static_cast<std::uint32_t>(tick);
}

struct LoopOutcome {
  std::int64_t ticks_run{0};
  bool diverged{false};           // the plant state became non-finite
  std::int64_t diverged_tick{-1};
  NonFiniteState diverged_state{};  // which component, its value and last finite value (state_guard.hpp)
  double wall_s{0.0};
  bool interrupted{false};        // stopped at a tick boundary by the tick sink (stop signal, failed log write)
};

// Tick sink concept (a bus log, tools/run/bus_log_sink.hpp): sees every tick's sensor frame and the
// controller's actuator frame of the same tick, right after the controller step, and may stop the loop at a
// tick boundary. Must not allocate. NoTickSink, the default, compiles away: the no-log loop is unchanged.
//   static constexpr bool kActive = true;
//   bool stop_requested();                                                  // polled before each tick
//   bool record(std::int64_t tick, const msg::SensorFrame&, const msg::ActuatorFrame&);  // false: stop
struct NoTickSink {
  static constexpr bool kActive = false;
  bool stop_requested() { return false; }
  bool record(std::int64_t, const msg::SensorFrame&, const msg::ActuatorFrame&) { return true; }
};

// Device concept:
//   void sense(std::int64_t tick, msg::SensorFrame& out);
//   void actuate(const msg::ActuatorFrame& cmd);
//   void advance(std::int64_t tick);
//   bool finite() const;
//   (optional) kGuardedStates, state_name(i), state_value(i) — state_guard.hpp
//   void record(double* row) const;          // Device::columns() names, in order
//   msg::ActuatorFrame initial_command() const;
//   auto& controller();                      // step(tick, const SensorFrame*, ActuatorFrame&)
// The plant's half of tick k, shared by the in-process loop and the plant process (lockstep runs are
// bit-identical to in-process because both run this code): the controller's command of tick k enters the
// latency pipe, the one due at k is applied (zero-order hold; until then the device's initial command), the
// plant integrates [k, k + 1), the guard checks the state and the recorder samples the row at k + 1.
// Returns false at the first non-finite state (`out` says where).
template <class Device>
class PlantTick {
 public:
  PlantTick(Device& device, const LoopConfig& cfg, Recorder* recorder)
      : device_(device), cfg_(cfg), recorder_(recorder), applied_(device.initial_command()) {}

  bool step(std::int64_t k, const msg::ActuatorFrame& command, LoopOutcome& out) {
    const int latency = cfg_.latency_ticks;
    if (latency == 0) {
      applied_ = command;
    } else {
      pipe_[static_cast<std::size_t>((k + latency) % (kMaxLatencyTicks + 1))] = command;
      if (k >= latency) applied_ = pipe_[static_cast<std::size_t>(k % (kMaxLatencyTicks + 1))];
    }
    device_.actuate(applied_);
    guard_.remember(device_);
    device_.advance(k);
    out.ticks_run = k + 1;
    if (!device_.finite()) {
      out.diverged = true;
      out.diverged_tick = k;
      out.diverged_state = guard_.locate(device_);
      return false;
    }
    if (recorder_ && recorder_->due(k + 1)) {
      if (double* row = recorder_->row(static_cast<double>(k + 1) * cfg_.tick_s())) device_.record(row);
    }
    return true;
  }

 private:
  Device& device_;
  const LoopConfig& cfg_;
  Recorder* recorder_;
  std::array<msg::ActuatorFrame, kMaxLatencyTicks + 1> pipe_{};
  msg::ActuatorFrame applied_;
  StateGuard<Device> guard_;
};

template <class Device, class Sink = NoTickSink>
LoopOutcome run_closed_loop(Device& device, const LoopConfig& cfg, Recorder* recorder, bool progress = false,
                            Sink* sink = nullptr) {
  LoopOutcome out;
  const std::int64_t ticks = cfg.ticks();
  PlantTick<Device> plant(device, cfg, recorder);
  msg::SensorFrame sensor{};
  msg::ActuatorFrame command{};
  const auto start = std::chrono::steady_clock::now();
  const bool show = progress && isatty(STDERR_FILENO);
  auto last_report = start;
  for (std::int64_t k = 0; k < ticks; ++k) {
    if constexpr (Sink::kActive) {
      if (sink != nullptr && sink->stop_requested()) {
        out.interrupted = true;
        break;
      }
    }
    device.sense(k, sensor);
    device.controller().step(static_cast<std::uint64_t>(k), &sensor, command);
    if constexpr (Sink::kActive) {
      if (sink != nullptr && !sink->record(k, sensor, command)) {
        out.interrupted = true;
        break;
      }
    }
    if (!plant.step(k, command, out)) break;
    if (show && (k & 0xFFFF) == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_report > std::chrono::seconds(1)) {
        last_report = now;
        std::fprintf(stderr, "\r%s: %5.1f %% of %.0f s simulated", cfg.name.c_str(),
                     100.0 * static_cast<double>(k) / static_cast<double>(ticks), cfg.duration_s);
      }
    }
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (show) std::fprintf(stderr, "\r%*s\r", 60, "");
  return out;
}

}  // namespace gyrostab::tools
