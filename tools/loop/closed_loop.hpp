// The in-process closed loop, one tick:
//   1. the plant samples its sensors: SensorFrame{tick k};
//   2. the controller (firmware) steps on it and returns ActuatorFrame{tick k};
//   3. the command computed from the frame of tick k is applied at tick k + latency (zero-order hold;
//      until then the plant's initial command), and the plant integrates [k, k + 1).
// Compiled once, against the plant and controller ports (plant_port.hpp, controller_port.hpp): three
// virtual calls per tick. Allocation-free: the latency pipe is a fixed array, the recorder's table is sized
// before the loop. A runtime guard stops at the first non-finite plant state and says at which tick and, for
// a plant that names its state (state_guard.hpp), which component with its last finite value.
// Docs: docs/architecture.md.
#pragma once

#include <array>
#include <cstdint>

#include "firmware/msg/any_frame.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "tools/loop/controller_port.hpp"
#include "tools/loop/loop_outcome.hpp"
#include "tools/loop/plant_port.hpp"
#include "tools/loop/recorder.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

using plants::begin_sensor_frame;

// Sees every tick's sensor frame and the actuator frame used for it, right after the exchange, and may stop
// the loop at a tick boundary (a bus log: tools/run/bus_log_sink.hpp). Must not allocate.
class TickSink {
 public:
  virtual ~TickSink() = default;
  virtual bool stop_requested() = 0;  // polled before each tick
  virtual bool record(std::int64_t tick, const msg::AnySensorFrame& sensor, const msg::AnyActuatorFrame& command) = 0;
};

// Sees each recorded row right after the recorder took it (a live view: tools/view/live_feed.hpp): the row's
// tick and its values, "t_s" first, as the CSV will hold them. Must not allocate or block.
class RowSink {
 public:
  virtual ~RowSink() = default;
  virtual void row(std::int64_t tick, const double* values) = 0;
};

// The plant's half of tick k, shared by the in-process loop, the plant process and re-simulation (lockstep
// runs are bit-identical to in-process because all of them run this code): the controller's command of tick
// k enters the latency pipe, the one due at k is applied (until then the plant's initial command), the plant
// integrates [k, k + 1), the guard checks the state and the recorder samples the row at k + 1.
// Returns false at the first non-finite state (`out` says where).
class PlantTick {
 public:
  PlantTick(PlantPort& plant, const LoopConfig& cfg, Recorder* recorder, RowSink* rows = nullptr);
  bool step(std::int64_t k, const msg::AnyActuatorFrame& command, LoopOutcome& out);

 private:
  PlantPort& plant_;
  const LoopConfig& cfg_;
  Recorder* recorder_;
  RowSink* rows_;
  std::array<msg::AnyActuatorFrame, kMaxLatencyTicks + 1> pipe_{};
  msg::AnyActuatorFrame applied_;
};

// Runs cfg.ticks() ticks (fewer when the plant diverges or the sink stops it). `progress`: a progress line on
// stderr when it is a terminal. `rows`: sees every recorded row (with a recorder).
LoopOutcome run_closed_loop(PlantPort& plant, ControllerPort& controller, const LoopConfig& cfg, Recorder* recorder,
                            bool progress = false, TickSink* sink = nullptr, RowSink* rows = nullptr);

}  // namespace gyrostab::tools
