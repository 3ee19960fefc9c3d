// The plant as every run mode sees it: one virtual call to sample the sensors and one to apply a command and
// integrate a tick. The run modes (in process, plant process, re-simulation) are compiled once against this
// port; what lies behind it — the device's composed plant in sim/plants/ with its meters — stays templated,
// so the per-step work is inlined inside step().
//
// A device implements the plant concept below and is wrapped by PlantPortOf<Binding>; the run modes see the
// device-independent frames (firmware/msg/any_frame.hpp), the binding its own typed ones:
//   using SensorFrame = ...; using ActuatorFrame = ...;     // the device's typed frames
//                                                           // (gyrostab_signals/<device>_frames.hpp)
//   void sense(std::int64_t tick, SensorFrame& out);        // the sensor frame of tick k
//   void actuate(const ActuatorFrame& cmd);                 // the command held over [k, k + 1)
//   void advance(std::int64_t tick);                        // integrate [k, k + 1) and feed the meters
//   bool finite() const;
//   (optional) using Record = ...; void record(Record& row) const;   // one CSV row: the signal table's
//                                                           // columns by name; none: it records nothing
//   (optional) nlohmann::json figures() const;              // report.json "figures"
//   (optional) kGuardedStates, state_name(i), state_value(i)   tools/loop/state_guard.hpp
//   (optional) nlohmann::json report_extra() const;         // blocks beside "figures" ("plant", "drift", ...)
//   (optional) nlohmann::json error_estimate() const;       // report.json "error_estimate"
//   (optional) nlohmann::json extra_timing(const LoopOutcome&) const;
//   (optional) ActuatorFrame initial_command() const;       // applied until the first command arrives
// Docs: docs/architecture.md.
#pragma once

#include <cstdint>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>

#include "firmware/msg/any_frame.hpp"
#include "tools/loop/loop_outcome.hpp"
#include "tools/loop/state_guard.hpp"

namespace gyrostab::tools {

class PlantPort {
 public:
  virtual ~PlantPort() = default;

  virtual void sense(std::int64_t tick, msg::AnySensorFrame& out) = 0;
  // Applies `command` and integrates tick k; false when the state became non-finite (`where` says which
  // component went first, for a plant that names its state).
  virtual bool step(std::int64_t tick, const msg::AnyActuatorFrame& command, NonFiniteState& where) = 0;
  virtual void record(double* row) const = 0;
  virtual msg::AnyActuatorFrame initial_command() const = 0;

  virtual nlohmann::json figures() const = 0;
  virtual nlohmann::json report_extra() const = 0;
  virtual nlohmann::json error_estimate() const = 0;
  virtual nlohmann::json extra_timing(const LoopOutcome& outcome) const = 0;
};

// The typed frames a binding exchanges: its own, generated from its signal table.
template <class Binding>
struct BindingFrames {
  using Sensor = typename Binding::SensorFrame;
  using Actuator = typename Binding::ActuatorFrame;
};

template <class Binding>
class PlantPortOf final : public PlantPort {
 public:
  using SensorFrame = typename BindingFrames<Binding>::Sensor;
  using ActuatorFrame = typename BindingFrames<Binding>::Actuator;

  template <class... Args>
  explicit PlantPortOf(Args&&... args) : b_(std::forward<Args>(args)...) {}

  void sense(std::int64_t tick, msg::AnySensorFrame& out) override {
    SensorFrame f{};
    b_.sense(tick, f);
    msg::to_any(f, out);
  }
  bool step(std::int64_t tick, const msg::AnyActuatorFrame& command, NonFiniteState& where) override {
    ActuatorFrame c;
    msg::from_any(command, c);
    b_.actuate(c);
    guard_.remember(b_);
    b_.advance(tick);
    if (b_.finite()) return true;
    where = guard_.locate(b_);
    return false;
  }
  void record(double* row) const override {
    if constexpr (requires { typename Binding::Record; }) {
      typename Binding::Record r{};
      b_.record(r);
      std::memcpy(row, &r, sizeof r);
    }
  }
  msg::AnyActuatorFrame initial_command() const override {
    msg::AnyActuatorFrame out{};
    if constexpr (requires(const Binding& b) { b.initial_command(); }) {
      msg::to_any(b_.initial_command(), out);
    }
    return out;
  }
  nlohmann::json figures() const override {
    if constexpr (requires(const Binding& b) { b.figures(); }) {
      return b_.figures();
    } else {
      return nlohmann::json::object();
    }
  }
  nlohmann::json report_extra() const override {
    if constexpr (requires(const Binding& b) { b.report_extra(); }) {
      return b_.report_extra();
    } else {
      return nlohmann::json::object();
    }
  }
  nlohmann::json error_estimate() const override {
    if constexpr (requires(const Binding& b) { b.error_estimate(); }) {
      return b_.error_estimate();
    } else {
      return {{"available", false}, {"why", "this device binding has no error estimate"}};
    }
  }
  nlohmann::json extra_timing(const LoopOutcome& outcome) const override {
    if constexpr (requires(const Binding& b) { b.extra_timing(outcome); }) {
      return b_.extra_timing(outcome);
    } else {
      return nlohmann::json::object();
    }
  }

  Binding& binding() { return b_; }
  const Binding& binding() const { return b_; }

 private:
  Binding b_;
  StateGuard<Binding> guard_;
};

template <class Binding, class... Args>
std::unique_ptr<PlantPort> make_plant_port(Args&&... args) {
  return std::make_unique<PlantPortOf<Binding>>(std::forward<Args>(args)...);
}

}  // namespace gyrostab::tools
